// The xArm controller's length, header and unknown-command rules
// (docs/protocol/servo-controller.md, "Framing"; xarm_emulator.hpp) exercised after other
// traffic, on the serial face and on the HID face: a completed command, a download in progress,
// a playing group, a half-received frame and a frame arriving while the controller is busy.
// Request and reply bytes are written by hand.
#include <gtest/gtest.h>

#include <array>
#include <string>

#include "runtime/emulator/hid_face.hpp"
#include "tests/emulator/emu_test_util.hpp"

namespace seqc::emu::test {
namespace {

constexpr const char* kBattery = "55 55 02 0f";
constexpr const char* kBatteryReply = "55 55 04 0f 4c 1d";

// Group 2, one action: servo 1 to 800 (0x0320) in 1000 ms (0x03e8), and each step's ack.
struct Step {
  const char* request;
  const char* ack;
};
constexpr std::array<Step, 5> kDownload = {{
    {"55 55 05 05 01 02 01", "55 55 04 05 01 00"},
    {"55 55 07 05 02 02 00 01 00", "55 55 04 05 02 00"},
    {"55 55 06 05 03 02 00 00", "55 55 04 05 03 00"},
    {"55 55 0c 05 04 02 00 00 0b e8 03 01 20 03", "55 55 04 05 04 00"},
    {"55 55 04 05 05 02", "55 55 04 05 05 00"},
}};

void expect_group_two_stored(const XArmEmulator& emu) {
  const auto stored = emu.stored_group(2);
  ASSERT_TRUE(stored.has_value());
  ASSERT_EQ(stored->size(), 1u);
  EXPECT_EQ((*stored)[0].time_ms, 1000);
  ASSERT_EQ((*stored)[0].servos.size(), 1u);
  EXPECT_EQ((*stored)[0].servos[0].id, 1);
  EXPECT_EQ((*stored)[0].servos[0].position, 800);
}

TEST(XArmReceiverStates, LenBelowTwoBadHeaderAndUnknownAfterACompletedCommand) {
  XArmEmulator emu;
  io::TimePoint t = at_ms(0);
  ASSERT_EQ(hex_of(exchange(emu, hex(kBattery), t)), kBatteryReply);
  EXPECT_EQ(hex_of(exchange(emu, hex("55 55 01 0f"), t)), "") << "LEN 1";
  EXPECT_EQ(hex_of(exchange(emu, hex("55 55 00 0f"), t)), "") << "LEN 0";
  EXPECT_EQ(hex_of(exchange(emu, hex("55 aa 02 0f"), t)), "") << "bad second header byte";
  EXPECT_EQ(hex_of(exchange(emu, hex("55 55 02 30"), t)), "") << "unknown command";
  EXPECT_EQ(hex_of(exchange(emu, hex(kBattery), t)), kBatteryReply);
  EXPECT_EQ(emu.frames_received(), 3u) << "the two batteries and the unknown command";
}

TEST(XArmReceiverStates, FramingRulesDuringADownloadLeaveItGoing) {
  XArmEmulator emu;
  io::TimePoint t = at_ms(0);
  ASSERT_EQ(hex_of(exchange(emu, hex(kDownload[0].request), t)), kDownload[0].ack);
  for (const char* noise :
       {"55 55 01 05", "55 55 00", "55 aa 05 05 02 02", "55 55 02 30", "55 55 03 0f 01"}) {
    EXPECT_EQ(hex_of(exchange(emu, hex(noise), t)), "") << noise;
    EXPECT_EQ(emu.downloading_group(), 2) << "after " << noise;
  }
  for (std::size_t i = 1; i < kDownload.size(); ++i) {
    EXPECT_EQ(hex_of(exchange(emu, hex(kDownload[i].request), t)), kDownload[i].ack) << i;
    if (i == 3) {
      // Between the action and the close: once more, a LEN 1 and an unknown command.
      EXPECT_EQ(hex_of(exchange(emu, hex("55 55 01 55 55 02 30"), t)), "");
    }
  }
  expect_group_two_stored(emu);
}

TEST(XArmReceiverStates, FramingRulesWhileAGroupPlays) {
  XArmEmulator emu;
  io::TimePoint t = at_ms(0);
  for (const Step& s : kDownload) ASSERT_EQ(hex_of(exchange(emu, hex(s.request), t)), s.ack);
  const io::TimePoint start = t + 1s;
  emu.receive(hex("55 55 05 06 02 02 00"), start);  // group 2, twice: 2 x 1000 ms
  EXPECT_EQ(hex_of(emu.take_output(start)), "55 55 05 06 02 02 00");
  emu.receive(hex("55 55 01 07"), start + 500ms);  // a Stop with LEN 1
  emu.receive(hex("55 55 02 30"), start + 600ms);
  emu.receive(hex("55 55 04 06 02 01"), start + 700ms);  // GroupRun one byte short
  emu.receive(hex("55 aa 02 07"), start + 800ms);
  EXPECT_EQ(hex_of(emu.take_output(start + 2000ms - io::Duration{1})), "");
  EXPECT_EQ(emu.playing_group(), 2);
  EXPECT_EQ(hex_of(emu.take_output(start + 2000ms)), "55 55 05 08 02 02 00");
}

TEST(XArmReceiverStates, AHalfReceivedFrameTakesTheNextHeaderAsItsData) {
  XArmEmulator emu;
  io::TimePoint t = at_ms(0);
  for (const Step& s : kDownload) ASSERT_EQ(hex_of(exchange(emu, hex(s.request), t)), s.ack);
  // Half a GroupRun of group 2, then a battery request: no inter-byte timeout, so its 55 55
  // are the run's times (0x5555) and 02 0f are noise. The run starts; the battery goes unasked.
  EXPECT_EQ(hex_of(exchange(emu, hex("55 55 05 06 02"), t)), "");
  EXPECT_EQ(hex_of(exchange(emu, hex(kBattery), t)), "55 55 05 06 02 55 55");
  EXPECT_EQ(emu.playing_group(), 2);
}

TEST(XArmReceiverStates, FramingRulesWhileBusyErasing) {
  XArmEmulator emu;  // step 1 keeps it busy erasing flash for 60 ms
  emu.receive(hex(kDownload[0].request), at_ms(0));
  emu.receive(hex("55 55 01"), at_ms(20));
  emu.receive(hex("55 55 02 30"), at_ms(30));
  emu.receive(hex(kBattery), at_ms(40));
  EXPECT_EQ(hex_of(emu.take_output(at_ms(60))), kDownload[0].ack) << "nothing for the others";
  const auto& r = emu.received();
  ASSERT_EQ(r.size(), 4u);
  EXPECT_FALSE(r[1].frame.has_value()) << "LEN 1 is never a frame, busy or not";
  EXPECT_FALSE(r[1].dropped_busy);
  EXPECT_TRUE(r[2].dropped_busy);
  EXPECT_TRUE(r[3].dropped_busy);
  io::TimePoint t = at_ms(60);
  for (std::size_t i = 1; i < kDownload.size(); ++i) {
    EXPECT_EQ(hex_of(exchange(emu, hex(kDownload[i].request), t)), kDownload[i].ack) << i;
  }
  expect_group_two_stored(emu);
}

// The HID face: one frame per 65-byte output report (report id 0, zero padding).
class XArmHidReceiverStates : public ::testing::Test {
 protected:
  void SetUp() override {
    auto opened = backend.open(kEmulatedHidPath);
    ASSERT_TRUE(opened.ok());
    device = std::move(*opened);
  }
  // Writes `frame_hex` in one report; returns the frame of the input report that answers it
  // within 100 ms, checked to be zero-padded to 64 bytes ("" when none comes).
  std::string send(const std::string& frame_hex) {
    Bytes report = hex("00 " + frame_hex);
    report.resize(65, 0x00);
    EXPECT_TRUE(device->write(report).ok()) << frame_hex;
    std::array<std::uint8_t, 64> in{};
    const transport::HidRead r = device->read(in, 100);
    if (r.state != transport::HidRead::State::Report) return "";
    EXPECT_EQ(r.count, 64u);
    const std::size_t len = std::size_t{in[2]} + 2;
    for (std::size_t i = len; i < in.size(); ++i) EXPECT_EQ(in[i], 0) << "padding at " << i;
    return hex_of(Bytes(in.begin(), in.begin() + static_cast<std::ptrdiff_t>(len)));
  }
  XArmEmulator emu;
  io::ManualClock clock;
  EmulatedHidBackend backend{emu, clock};
  std::unique_ptr<transport::HidDevice> device;
};

TEST_F(XArmHidReceiverStates, LenBelowTwoBadHeaderAndUnknownAfterACompletedCommand) {
  ASSERT_EQ(send(kBattery), kBatteryReply);
  EXPECT_EQ(send("55 55 01 0f"), "");
  EXPECT_EQ(send("55 55 00 0f"), "");
  EXPECT_EQ(send("55 aa 02 0f"), "");
  EXPECT_EQ(send("aa 55 55 02 0f"), "") << "the frame must start the report";
  EXPECT_EQ(send("55 55 02 30"), "");
  EXPECT_EQ(send(kBattery), kBatteryReply);
  EXPECT_EQ(emu.frames_received(), 3u);
}

TEST_F(XArmHidReceiverStates, FramingRulesDuringADownloadLeaveItGoing) {
  ASSERT_EQ(send(kDownload[0].request), kDownload[0].ack);
  ASSERT_EQ(send(kDownload[1].request), kDownload[1].ack);
  for (const char* noise : {"55 55 01 05", "55 55 00", "55 aa 05 05 03 02 00 00", "55 55 02 30"}) {
    EXPECT_EQ(send(noise), "") << noise;
    EXPECT_EQ(emu.downloading_group(), 2) << "after " << noise;
  }
  for (std::size_t i = 2; i < kDownload.size(); ++i) {
    EXPECT_EQ(send(kDownload[i].request), kDownload[i].ack) << i;
  }
  expect_group_two_stored(emu);
}

}  // namespace
}  // namespace seqc::emu::test
