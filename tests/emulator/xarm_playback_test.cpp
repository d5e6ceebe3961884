// Stored groups play in emulated time: GroupRun/Stop/Speed and the notifications.
#include <gtest/gtest.h>

#include "tests/emulator/emu_test_util.hpp"

namespace seqc::emu::test {
namespace {

// Group 1: servo 1 to 700 in 100 ms, servo 1 to 300 in 200 ms, servo 2 to 900 in 300 ms.
std::vector<lsc::GroupAction> three_actions() {
  return {lsc::GroupAction{100, {{1, 700}}}, lsc::GroupAction{200, {{1, 300}}},
          lsc::GroupAction{300, {{2, 900}}}};
}

class XArmPlayback : public ::testing::Test {
 protected:
  void SetUp() override {
    io::TimePoint t{0};
    ASSERT_TRUE(download(emu, 1, three_actions(), t));
    t0 = at_ms(1000);
    ASSERT_GE(t0, t);
  }
  // Position of `id` at t0 + ms, after running emulated time to it.
  std::uint16_t pos(std::uint8_t id, std::int64_t ms) {
    emu.advance_to(t0 + std::chrono::milliseconds(ms));
    return emu.servo_position(id, t0 + std::chrono::milliseconds(ms));
  }
  XArmEmulator emu;
  io::TimePoint t0{0};
};

TEST_F(XArmPlayback, RunTwiceNotifiesStartAndFinishAtTheRightTimes) {
  emu.receive(hex("55 55 05 06 01 02 00"), t0);  // group 1, twice
  EXPECT_EQ(emu.next_output_at(), t0);
  EXPECT_EQ(hex_of(emu.take_output(t0)), "55 55 05 06 01 02 00");
  // Two loops of 600 ms: GroupFinished due at t0 + 1200 ms, not a moment earlier.
  EXPECT_EQ(emu.next_output_at(), t0 + 1200ms);
  EXPECT_EQ(pos(1, 50), 600);
  EXPECT_EQ(pos(1, 200), 500);
  EXPECT_EQ(pos(2, 450), 700);
  EXPECT_EQ(pos(1, 650), 500) << "second loop, action 0 again (from 300 to 700)";
  EXPECT_EQ(emu.take_output(t0 + 1200ms - io::Duration{1}), Bytes{});
  EXPECT_EQ(emu.playing_group(), std::optional<std::uint8_t>(1));
  EXPECT_EQ(hex_of(emu.take_output(t0 + 1200ms)), "55 55 05 08 01 02 00");
  EXPECT_FALSE(emu.playing_group().has_value());
  EXPECT_EQ(emu.next_output_at(), std::nullopt);
  EXPECT_EQ(pos(2, 5000), 900);
}

TEST_F(XArmPlayback, SpeedPercentScalesTime) {
  io::TimePoint t = t0;
  EXPECT_EQ(exchange(emu, hex("55 55 05 0b 01 c8 00"), t), Bytes{});  // group 1 at 200 %
  EXPECT_EQ(emu.group_speed(1), 200);
  emu.receive(hex("55 55 05 06 01 01 00"), t0);
  EXPECT_EQ(hex_of(emu.take_output(t0)), "55 55 05 06 01 01 00");
  EXPECT_EQ(emu.next_output_at(), t0 + 300ms);
  EXPECT_EQ(pos(1, 25), 600);
  EXPECT_EQ(hex_of(emu.take_output(t0 + 300ms)), "55 55 05 08 01 01 00");
  // 50 % for every group (255): twice as slow.
  const io::TimePoint t1 = t0 + 1000ms;
  emu.receive(hex("55 55 05 0b ff 32 00"), t1);
  emu.receive(hex("55 55 05 06 01 01 00"), t1);
  EXPECT_EQ(hex_of(emu.take_output(t1)), "55 55 05 06 01 01 00");
  EXPECT_EQ(emu.next_output_at(), t1 + 1200ms);
  // Speed is volatile.
  emu.power_cycle(t1 + 10ms);
  EXPECT_EQ(emu.group_speed(1), 100);
  EXPECT_FALSE(emu.playing_group().has_value());
}

TEST_F(XArmPlayback, SpeedChangeWhilePlayingRescalesTheRest) {
  emu.receive(hex("55 55 05 06 01 01 00"), t0);
  EXPECT_EQ(hex_of(emu.take_output(t0)), "55 55 05 06 01 01 00");
  // Half way through action 0 (servo 1 at 600), speed 200 %: 50 ms left become 25 ms.
  emu.receive(hex("55 55 05 0b 01 c8 00"), t0 + 50ms);
  EXPECT_EQ(pos(1, 50), 600);
  EXPECT_EQ(pos(1, 75), 700);
  // Then 100 ms + 150 ms: finished at 325 ms.
  EXPECT_EQ(emu.next_output_at(), t0 + 325ms);
  EXPECT_EQ(hex_of(emu.take_output(t0 + 325ms)), "55 55 05 08 01 01 00");
}

TEST_F(XArmPlayback, LoopForeverUntilStopped) {
  emu.receive(hex("55 55 05 06 01 00 00"), t0);  // times 0 = loop
  EXPECT_EQ(hex_of(emu.take_output(t0)), "55 55 05 06 01 00 00");
  EXPECT_EQ(emu.next_output_at(), std::nullopt) << "a loop never finishes by itself";
  EXPECT_EQ(emu.take_output(t0 + 60s), Bytes{});
  EXPECT_EQ(emu.playing_group(), std::optional<std::uint8_t>(1));
  // 60 s = 100 loops of 600 ms; 60.05 s is half way through action 0 again.
  EXPECT_EQ(pos(1, 60050), 500);
  const io::TimePoint stop_at = t0 + 60050ms;
  emu.receive(hex("55 55 02 07"), stop_at);
  EXPECT_EQ(hex_of(emu.take_output(stop_at)), "55 55 02 07");
  EXPECT_FALSE(emu.playing_group().has_value());
  // The servo finishes the move it was given and no further action starts.
  EXPECT_EQ(pos(1, 61000), 700);
  EXPECT_EQ(pos(2, 62000), 900);
}

TEST_F(XArmPlayback, GroupRunOfAnotherGroupReplacesAndEraseStops) {
  io::TimePoint t = t0;
  ASSERT_TRUE(download(emu, 2, {lsc::GroupAction{1000, {{3, 0}}}}, t));
  const io::TimePoint t1 = t;
  emu.receive(hex("55 55 05 06 01 00 00"), t1);
  emu.receive(hex("55 55 05 06 02 03 00"), t1 + 10ms);
  EXPECT_EQ(hex_of(emu.take_output(t1 + 10ms)), "55 55 05 06 01 00 00 55 55 05 06 02 03 00");
  EXPECT_EQ(emu.playing_group(), std::optional<std::uint8_t>(2));
  EXPECT_EQ(emu.next_output_at(), t1 + 3010ms);
  // Erasing the playing group stops it without a GroupFinished.
  emu.receive(hex("55 55 03 08 02"), t1 + 500ms);
  EXPECT_EQ(hex_of(emu.take_output(t1 + 10s)), "55 55 02 08");
  EXPECT_FALSE(emu.playing_group().has_value());
}

}  // namespace
}  // namespace seqc::emu::test
