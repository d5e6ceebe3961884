// The receive half of the emulated UART (InputLine) and the xArm behind it on a pty
// (ControllerPtyDevice), in emulated time: the host's bytes reach the controller one byte time
// apart, a frame is processed only when its last byte has arrived, and the in-process
// EmulatorTransport follows the same model.
#include <gtest/gtest.h>

#include <array>

#include "runtime/emulator/emulator_transport.hpp"
#include "runtime/emulator/group_dump.hpp"
#include "runtime/emulator/pty_device.hpp"
#include "tests/emulator/emu_test_util.hpp"

namespace seqc::emu::test {
namespace {

// 10 bits at 9600 baud, as the emulator rounds it (to the nanosecond below).
constexpr io::Duration kByte9600{1'041'666};

TEST(InputLine, EachByteTakesItsWireTimeAndQueuesBehindTheLineBusy) {
  InputLine line(9600);
  EXPECT_EQ(line.byte_time(), kByte9600);
  EXPECT_FALSE(line.next_delivery_at());
  // Three bytes written at 10 ms: delivered at 10 ms + 1, 2, 3 byte times.
  EXPECT_EQ(line.push(hex("55 55 02"), at_ms(10)), at_ms(10) + 3 * kByte9600);
  // One more written while the line is still busy queues behind them.
  EXPECT_EQ(line.push(hex("0f"), at_ms(11)), at_ms(10) + 4 * kByte9600);
  EXPECT_EQ(line.next_delivery_at(), at_ms(10) + kByte9600);

  EXPECT_TRUE(line.take(at_ms(10) + kByte9600 - io::Duration{1}).empty());
  auto got = line.take(at_ms(10) + 2 * kByte9600);
  ASSERT_EQ(got.size(), 2u);
  EXPECT_EQ(got[0].at, at_ms(10) + kByte9600);
  EXPECT_EQ(hex_of(got[0].bytes), "55");
  EXPECT_EQ(got[1].at, at_ms(10) + 2 * kByte9600);
  EXPECT_EQ(hex_of(got[1].bytes), "55");
  got = line.take(at_ms(100));
  ASSERT_EQ(got.size(), 2u);
  EXPECT_EQ(got[1].at, at_ms(10) + 4 * kByte9600);
  EXPECT_EQ(hex_of(got[1].bytes), "0f");
  EXPECT_TRUE(line.empty());

  // After an idle line, a write starts from its own time, not from the last delivery.
  EXPECT_EQ(line.push(hex("55"), at_ms(50)), at_ms(50) + kByte9600);
}

TEST(InputLine, UnpacedDeliversAWriteAtOnceInOnePiece) {
  InputLine line(0);
  EXPECT_EQ(line.push(hex("55 55 02 0f"), at_ms(7)), at_ms(7));
  const auto got = line.take(at_ms(7));
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0].at, at_ms(7));
  EXPECT_EQ(hex_of(got[0].bytes), "55 55 02 0f");
}

XArmConfig paced_9600() {
  XArmConfig config;
  config.baud = 9600;
  return config;
}

TEST(ControllerPtyDevice, AFrameIsProcessedOnlyAfterItsLastByteArrived) {
  XArmEmulator emu(paced_9600());
  ControllerPtyDevice device(emu);
  // The whole GetBatteryVoltage frame is written at once at 0.
  device.receive(hex("55 55 02 0f"), at_ms(0));
  EXPECT_TRUE(emu.received_bytes().empty()) << "nothing has crossed the wire yet";
  EXPECT_EQ(device.next_output_at(), at_ms(0) + 4 * kByte9600) << "wake when the frame is in";
  EXPECT_TRUE(device.take_output(at_ms(0) + 3 * kByte9600).empty());
  EXPECT_EQ(hex_of(emu.received_bytes()), "55 55 02");
  EXPECT_TRUE(emu.received().empty()) << "three bytes are not a frame";

  // The server woke late: the last byte is still handed over at its own arrival time.
  EXPECT_TRUE(device.take_output(at_ms(0) + 4 * kByte9600 + io::Duration{10}).empty());
  ASSERT_EQ(emu.received().size(), 1u);
  EXPECT_EQ(emu.received()[0].at, at_ms(0) + 4 * kByte9600);
  EXPECT_FALSE(device.input_pending());

  // The reply 55 55 04 0f 4c 1d follows: its first byte is due one byte time after the
  // frame was processed, its last after six. The device wakes the server for the whole
  // reply, but a server that wakes earlier gets the bytes already due, never more.
  EXPECT_EQ(device.next_output_at(), at_ms(0) + 10 * kByte9600);
  EXPECT_EQ(hex_of(device.take_output(at_ms(0) + 9 * kByte9600)), "55 55 04 0f 4c");
  EXPECT_EQ(hex_of(device.take_output(at_ms(0) + 10 * kByte9600)), "1d");
  EXPECT_FALSE(device.next_output_at());
}

TEST(ControllerPtyDevice, BackToBackWritesQueueOnTheLine) {
  XArmEmulator emu(paced_9600());
  ControllerPtyDevice device(emu);
  // Two frames written 1 ms apart: the second cannot start before the first is through.
  device.receive(hex("55 55 02 0f"), at_ms(0));
  device.receive(hex("55 55 05 15 02 01 06"), at_ms(1));
  (void)device.take_output(at_ms(1000));
  ASSERT_EQ(emu.received().size(), 2u);
  EXPECT_EQ(emu.received()[0].at, at_ms(0) + 4 * kByte9600);
  EXPECT_EQ(emu.received()[1].at, at_ms(0) + 11 * kByte9600);
}

TEST(ControllerPtyDevice, WakesWhenEachFrameIsInNotAtEveryByte) {
  XArmEmulator emu(paced_9600());
  ControllerPtyDevice device(emu);
  // Garbage, then two frames in one write: the first frame is in after 6 bytes.
  device.receive(hex("00 01 55 55 02 0f 55 55 05 15 02 01 06"), at_ms(0));
  EXPECT_EQ(device.next_output_at(), at_ms(0) + 6 * kByte9600);
  EXPECT_TRUE(device.take_output(at_ms(0) + 6 * kByte9600).empty());
  // Each garbage byte is known to be garbage as it arrives: a piece each, then the frame.
  ASSERT_EQ(emu.received().size(), 3u);
  EXPECT_EQ(hex_of(emu.received()[1].raw), "01");
  EXPECT_FALSE(emu.received()[1].frame);
  EXPECT_EQ(emu.received()[1].at, at_ms(0) + 2 * kByte9600);
  // The battery reply ends at 12 byte times, before the second frame is in (13).
  EXPECT_EQ(device.next_output_at(), at_ms(0) + 12 * kByte9600);
  EXPECT_EQ(hex_of(device.take_output(at_ms(0) + 12 * kByte9600)), "55 55 04 0f 4c 1d");
  EXPECT_EQ(device.next_output_at(), at_ms(0) + 13 * kByte9600);
  EXPECT_TRUE(device.take_output(at_ms(0) + 13 * kByte9600).empty());
  ASSERT_EQ(emu.received().size(), 4u);
  EXPECT_EQ(device.next_output_at(), at_ms(0) + 24 * kByte9600) << "11 bytes of positions";
}

TEST(ControllerPtyDevice, AnUnfinishedFrameStillReachesTheController) {
  XArmEmulator emu(paced_9600());
  ControllerPtyDevice device(emu);
  device.receive(hex("55 55 02"), at_ms(0));
  EXPECT_EQ(device.next_output_at(), at_ms(0) + 3 * kByte9600) << "the last queued byte";
  (void)device.take_output(at_ms(0) + 3 * kByte9600);
  EXPECT_EQ(hex_of(emu.received_bytes()), "55 55 02");
  EXPECT_FALSE(device.next_output_at());
}

TEST(ControllerPtyDevice, UnpacedDeliversOnReceive) {
  XArmEmulator emu;  // baud 0
  ControllerPtyDevice device(emu);
  device.receive(hex("55 55 02 0f"), at_ms(3));
  ASSERT_EQ(emu.received().size(), 1u);
  EXPECT_EQ(emu.received()[0].at, at_ms(3));
  EXPECT_EQ(hex_of(device.take_output(at_ms(3))), "55 55 04 0f 4c 1d");
}

TEST(ControllerPtyDevice, HangUpDropsWhatIsStillOnTheLine) {
  XArmConfig config = paced_9600();
  config.faults.hangup_at = 1;
  XArmEmulator emu(config);
  ControllerPtyDevice device(emu);
  device.receive(hex("55 55 02 0f 55 55 02 0f"), at_ms(0));
  (void)device.take_output(at_ms(0) + 4 * kByte9600);
  EXPECT_TRUE(device.hung_up());
  EXPECT_FALSE(device.input_pending());
  EXPECT_EQ(hex_of(emu.received_bytes()), "55 55 02 0f");
}

// The same request through EmulatorTransport on a ManualClock and through the pty device
// reaches the controller at the same emulated time and is answered at the same time.
TEST(ControllerPtyDevice, SameTimelineAsEmulatorTransport) {
  const Bytes request = hex("55 55 05 15 02 01 06");
  XArmEmulator via_pty(paced_9600());
  ControllerPtyDevice device(via_pty);
  device.receive(request, at_ms(20));
  io::TimePoint t = at_ms(20);
  Bytes pty_reply;
  while (auto next = device.next_output_at()) {
    t = *next;
    const Bytes got = device.take_output(t);
    pty_reply.insert(pty_reply.end(), got.begin(), got.end());
  }

  XArmEmulator in_process(paced_9600());
  io::ManualClock clock(at_ms(20));
  EmulatorTransport link(in_process, clock);
  ASSERT_TRUE(link.write(request).ok());
  Bytes link_reply;
  std::array<std::uint8_t, 64> buf{};
  while (true) {
    const io::ReadResult r = link.read(buf, at_ms(500));
    if (r.status != io::ReadStatus::Data) break;
    link_reply.insert(link_reply.end(), buf.begin(), buf.begin() + static_cast<long>(r.count));
    if (link_reply.size() == pty_reply.size()) break;
  }
  EXPECT_EQ(hex_of(pty_reply), "55 55 09 15 02 01 f4 01 06 f4 01");
  EXPECT_EQ(link_reply, pty_reply);
  ASSERT_EQ(via_pty.received().size(), 1u);
  ASSERT_EQ(in_process.received().size(), 1u);
  EXPECT_EQ(via_pty.received()[0].at, in_process.received()[0].at);
  EXPECT_EQ(via_pty.received()[0].at, at_ms(20) + 7 * kByte9600);
  EXPECT_EQ(t, at_ms(20) + 18 * kByte9600) << "7 bytes in, 11 bytes out";
  EXPECT_EQ(clock.now(), t);
}

TEST(GroupDump, ListsEveryValidGroupActionByAction) {
  XArmEmulator emu;
  io::TimePoint t{0};
  EXPECT_EQ(dump_groups(emu),
            "# seqc emulate xarm: stored groups\n"
            "# group index time_ms id=position ...\n");
  ASSERT_TRUE(download(emu, 7, {lsc::GroupAction{250, {{1, 100}, {6, 1000}}}}, t));
  ASSERT_TRUE(download(
      emu, 2, {lsc::GroupAction{1000, {{1, 500}, {2, 0}}}, lsc::GroupAction{65535, {{3, 250}}}},
      t));
  // A download that never reaches step 5 leaves its group out.
  (void)exchange(emu, hex("55 55 05 05 01 09 01"), t);
  EXPECT_EQ(dump_groups(emu),
            "# seqc emulate xarm: stored groups\n"
            "# group index time_ms id=position ...\n"
            "2 0 1000 1=500 2=0\n"
            "2 1 65535 3=250\n"
            "7 0 250 1=100 6=1000\n");
}

}  // namespace
}  // namespace seqc::emu::test
