// Every other command of docs/protocol/servo-controller.md: effects and exact reply bytes
// (hand-written).
#include <gtest/gtest.h>

#include "runtime/emulator/pty_device.hpp"
#include "tests/emulator/emu_test_util.hpp"

namespace seqc::emu::test {
namespace {

TEST(XArmCommands, BatteryVoltage) {
  XArmEmulator emu;
  io::TimePoint t{0};
  EXPECT_EQ(hex_of(exchange(emu, hex("55 55 02 0f"), t)), "55 55 04 0f 4c 1d");
  XArmConfig low;
  low.battery_mv = 6400;
  XArmEmulator emu2(low);
  EXPECT_EQ(hex_of(exchange(emu2, hex("55 55 02 0f"), t)), "55 55 04 0f 00 19");
}

TEST(XArmCommands, MoveIsLinearAndReadableWhileMoving) {
  XArmEmulator emu;
  io::TimePoint t = at_ms(1000);
  // Servo 1 to 800 and servo 2 to 200 in 1000 ms; servo 3 "no move" (00 ff).
  EXPECT_EQ(exchange(emu, hex("55 55 0e 03 03 e8 03 01 20 03 02 c8 00 03 00 ff"), t), Bytes{});
  EXPECT_EQ(emu.servo_position(1, at_ms(1000)), 500);
  EXPECT_EQ(emu.servo_position(1, at_ms(1250)), 575);
  EXPECT_EQ(emu.servo_position(2, at_ms(1500)), 350);
  EXPECT_EQ(emu.servo_position(1, at_ms(2000)), 800);
  EXPECT_EQ(emu.servo_position(1, at_ms(9000)), 800);
  EXPECT_EQ(emu.servo_position(3, at_ms(2000)), 500);
  // ServoPositionRead of 1, 2, 3 half way: 650, 350, 500.
  t = at_ms(1500);
  EXPECT_EQ(hex_of(exchange(emu, hex("55 55 06 15 03 01 02 03"), t)),
            "55 55 0c 15 03 01 8a 02 02 5e 01 03 f4 01");
  // Unknown ids are left out of the reply.
  EXPECT_EQ(hex_of(exchange(emu, hex("55 55 05 15 02 09 06"), t)), "55 55 06 15 01 06 f4 01");
  // A target beyond the servo's range is clamped to it.
  EXPECT_EQ(exchange(emu, hex("55 55 08 03 01 00 00 04 d0 07"), t), Bytes{});
  EXPECT_EQ(emu.servo_position(4, t), 1000);
}

TEST(XArmCommands, PositionReadLeavesAbsentServosOut) {
  XArmEmulator emu;  // six servos, ids 1-6
  io::TimePoint t = at_ms(0);
  // Asking for 9 only: a reply with count 0 and nothing else.
  EXPECT_EQ(hex_of(exchange(emu, hex("55 55 04 15 01 09"), t)), "55 55 03 15 00");
  // 2, 9 and 6: only the two on the bus, in the order asked.
  EXPECT_EQ(hex_of(exchange(emu, hex("55 55 06 15 03 02 09 06"), t)),
            "55 55 09 15 02 02 f4 01 06 f4 01");
}

TEST(XArmCommands, ServoOffUnpowersWhereItIs) {
  XArmEmulator emu;
  io::TimePoint t{0};
  exchange(emu, hex("55 55 08 03 01 e8 03 05 e8 03"), t);  // servo 5 to 1000 in 1 s
  t = at_ms(400);
  EXPECT_EQ(exchange(emu, hex("55 55 04 14 01 05"), t), Bytes{});
  EXPECT_FALSE(emu.servos().powered(5));
  EXPECT_EQ(emu.servo_position(5, at_ms(900)), 700);
  EXPECT_TRUE(emu.servos().powered(4));
}

TEST(XArmCommands, OffsetsAdjustIsVolatileWriteIsKept) {
  XArmEmulator emu;
  io::TimePoint t{0};
  // Adjust servo 1 by -10 and servo 2 by +25; read both.
  EXPECT_EQ(exchange(emu, hex("55 55 05 18 01 f6 ff"), t), Bytes{});
  EXPECT_EQ(exchange(emu, hex("55 55 05 18 02 19 00"), t), Bytes{});
  EXPECT_EQ(hex_of(exchange(emu, hex("55 55 05 17 02 01 02"), t)), "55 55 07 17 02 01 f6 02 19");
  // Write servo 1 only, then power cycle: servo 1 keeps -10, servo 2 loses its offset.
  EXPECT_EQ(exchange(emu, hex("55 55 04 16 01 01"), t), Bytes{});
  emu.power_cycle(t);
  EXPECT_EQ(hex_of(exchange(emu, hex("55 55 05 17 02 01 02"), t)), "55 55 07 17 02 01 f6 02 00");
  // An offset that does not fit the reply's signed byte is ignored.
  EXPECT_EQ(exchange(emu, hex("55 55 05 18 01 2c 01"), t), Bytes{});
  EXPECT_EQ(emu.servos().offset(1), -10);
}

TEST(XArmCommands, ServoSpeedStoresModeUntilPowerCycle) {
  XArmEmulator emu;
  io::TimePoint t{0};
  EXPECT_EQ(exchange(emu, hex("55 55 06 1a 03 01 e8 03"), t), Bytes{});
  EXPECT_EQ(emu.servos().mode(3), lsc::ServoMode::Motor);
  EXPECT_EQ(emu.servos().mode_milliseconds(3), 1000);
  emu.power_cycle(t);
  EXPECT_EQ(emu.servos().mode(3), lsc::ServoMode::Servo);
}

TEST(XArmCommands, BusServoInfoWriteThenRead) {
  XArmEmulator emu;
  io::TimePoint t{0};
  // Default limits: 0..1000, no voltage or temperature limits; servo 1 at 500, 32 C, 7500 mV.
  EXPECT_EQ(hex_of(exchange(emu, hex("55 55 02 1c"), t)),
            "55 55 15 1c 01 00 00 e8 03 00 00 00 00 00 00 00 00 00 f4 01 20 4c 1d");
  // Limits 100..900, 7000..20000 mV, 85 C, LED enabled, all warnings.
  EXPECT_EQ(exchange(emu, hex("55 55 0f 1b 01 64 00 84 03 58 1b 20 4e 55 00 00 07"), t), Bytes{});
  exchange(emu, hex("55 55 05 18 01 fb ff"), t);  // offset -5
  EXPECT_EQ(hex_of(exchange(emu, hex("55 55 02 1c"), t)),
            "55 55 15 1c 01 64 00 84 03 58 1b 20 4e 55 00 00 07 fb f4 01 20 4c 1d");
  // The new limits clamp moves (servo 2 too: the write reaches every servo on the bus).
  exchange(emu, hex("55 55 08 03 01 00 00 02 e8 03"), t);
  EXPECT_EQ(emu.servo_position(2, t), 900);
  // Limits are kept over a power cycle.
  emu.power_cycle(t);
  EXPECT_EQ(emu.servos().limits(1).position_max, 900);
}

TEST(XArmCommands, GroupEraseRepliesEmptyFrame) {
  XArmEmulator emu;
  io::TimePoint t{0};
  ASSERT_TRUE(download(emu, 9, {test_action(1)}, t));
  ASSERT_TRUE(download(emu, 10, {test_action(2)}, t));
  const io::TimePoint sent = t;
  EXPECT_EQ(hex_of(exchange(emu, hex("55 55 03 08 09"), t)), "55 55 02 08");
  EXPECT_EQ(t - sent, 60ms) << "erasing flash keeps the controller busy";
  EXPECT_FALSE(emu.stored_group(9).has_value());
  EXPECT_TRUE(emu.stored_group(10).has_value());
  EXPECT_EQ(hex_of(exchange(emu, hex("55 55 03 08 ff"), t)), "55 55 02 08");
  EXPECT_FALSE(emu.stored_group(10).has_value());
}

TEST(XArmCommands, UnknownAndMalformedFramesAreIgnoredButRecorded) {
  XArmEmulator emu;
  io::TimePoint t{0};
  // An unknown command, a battery request with stray data, garbage, a LEN below 2.
  EXPECT_EQ(exchange(emu, hex("55 55 03 30 01"), t), Bytes{});
  EXPECT_EQ(exchange(emu, hex("55 55 03 0f 01"), t), Bytes{});
  EXPECT_EQ(exchange(emu, hex("01 02 03"), t), Bytes{});
  EXPECT_EQ(exchange(emu, hex("55 55 01"), t), Bytes{});
  // Still answering afterwards; garbage before a frame does not hide it.
  EXPECT_EQ(hex_of(exchange(emu, hex("aa 01 55 55 02 0f"), t)), "55 55 04 0f 4c 1d");
  const auto& r = emu.received();
  ASSERT_EQ(r.size(), 6u);
  EXPECT_EQ(r[0].frame, (lsc::Frame{0x30, {0x01}}));
  EXPECT_EQ(r[1].frame, (lsc::Frame{0x0f, {0x01}}));
  EXPECT_EQ(hex_of(r[2].raw), "01 02 03");
  EXPECT_FALSE(r[2].frame.has_value());
  EXPECT_EQ(hex_of(r[3].raw), "55 55 01");
  EXPECT_FALSE(r[3].frame.has_value());
  EXPECT_EQ(hex_of(r[4].raw), "aa 01");
  EXPECT_EQ(hex_of(r[5].raw), "55 55 02 0f");
  EXPECT_EQ(hex_of(emu.received_bytes()),
            "55 55 03 30 01 55 55 03 0f 01 01 02 03 55 55 01 aa 01 55 55 02 0f");
  EXPECT_EQ(emu.frames_received(), 3u) << "only framed requests count";
}

TEST(XArmCommands, AFrameWaitsForItsLastByteHoweverLong) {
  // Like the firmware: no inter-byte timeout. A client writing byte by byte with pauses.
  XArmEmulator emu;
  const Bytes request = hex("55 55 02 0f");
  io::TimePoint t = at_ms(0);
  for (std::uint8_t b : request) {
    emu.receive(ByteView(&b, 1), t);
    t += 500ms;
  }
  EXPECT_EQ(hex_of(emu.take_output(t)), "55 55 04 0f 4c 1d");
  ASSERT_EQ(emu.received().size(), 1u);
  EXPECT_TRUE(emu.received()[0].frame.has_value());
}

TEST(XArmCommands, WithoutTheGapFaultACorruptedLenSwallowsTheNextFrame) {
  XArmEmulator emu;
  emu.receive(hex("55 55 20 0f"), at_ms(0));
  emu.receive(hex("55 55 02 0f"), at_ms(30));
  EXPECT_EQ(hex_of(emu.take_output(at_ms(1000))), "") << "still inside the first frame";
}

TEST(XArmCommands, IdleGapDiscardsPartialFrame) {
  XArmConfig config;
  config.faults.frame_gap = 20ms;  // the opt-in fault: frame-gap=20ms
  XArmEmulator emu(config);
  // A corrupted LEN (0x20 instead of 0x02) would swallow the next frames...
  emu.receive(hex("55 55 20 0f"), at_ms(0));
  // ...but after 30 ms of silence the partial frame is dropped.
  emu.receive(hex("55 55 02 0f"), at_ms(30));
  EXPECT_EQ(hex_of(emu.take_output(at_ms(30))), "55 55 04 0f 4c 1d");
  ASSERT_EQ(emu.received().size(), 2u);
  EXPECT_EQ(hex_of(emu.received()[0].raw), "55 55 20 0f");
  EXPECT_FALSE(emu.received()[0].frame.has_value());
  // Within the gap, the bytes continue the partial frame (as on a real UART).
  XArmEmulator emu2(config);
  emu2.receive(hex("55 55 05 15"), at_ms(0));
  emu2.receive(hex("02 01 02"), at_ms(10));
  EXPECT_EQ(hex_of(emu2.take_output(at_ms(10))), "55 55 09 15 02 01 f4 01 02 f4 01");
}

TEST(XArmCommands, TheSplitFaultHandsARepliesOverInTwoPieces) {
  XArmConfig config;
  config.baud = 9600;
  config.faults.split = 1.0;
  XArmEmulator emu(config);
  ControllerPtyDevice device(emu);
  device.receive(hex("55 55 02 0f"), at_ms(0));
  Bytes whole;
  int pieces = 0;
  while (auto at = device.next_output_at()) {
    const Bytes got = device.take_output(*at);
    if (got.empty()) continue;
    ++pieces;
    whole.insert(whole.end(), got.begin(), got.end());
  }
  EXPECT_EQ(pieces, 2);
  EXPECT_EQ(hex_of(whole), "55 55 04 0f 4c 1d") << "nothing lost or reordered";
}

TEST(XArmCommands, RepliesArePacedByBaud) {
  XArmConfig config;
  config.baud = 9600;  // 1.041666 ms per byte
  XArmEmulator emu(config);
  emu.receive(hex("55 55 02 0f"), at_ms(0));
  const io::Duration byte = io::Duration{10'000'000'000LL / 9600};
  EXPECT_EQ(emu.next_output_at(), io::TimePoint{byte});
  EXPECT_EQ(hex_of(emu.take_output(io::TimePoint{byte * 3})), "55 55 04");
  EXPECT_EQ(emu.next_output_at(), io::TimePoint{byte * 4});
  // A second request while the first reply is still on the wire queues behind it.
  emu.receive(hex("55 55 02 0f"), io::TimePoint{byte * 3});
  EXPECT_EQ(hex_of(emu.take_output(io::TimePoint{byte * 6})), "0f 4c 1d");
  EXPECT_EQ(hex_of(emu.take_output(io::TimePoint{byte * 12 - io::Duration{1}})), "55 55 04 0f 4c");
  EXPECT_EQ(hex_of(emu.take_output(io::TimePoint{byte * 12})), "1d");
}

}  // namespace
}  // namespace seqc::emu::test
