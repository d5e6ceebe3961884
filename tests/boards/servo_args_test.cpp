// What a servo controller accepts as servos, targets, times and groups
// (runtime/boards/servo_args.hpp): every value outside its field's range is an error naming the
// field and the range, never wrapped.
#include <gtest/gtest.h>

#include "runtime/boards/servo_args.hpp"

namespace seqc::boards {
namespace {

std::optional<compiler::RobotInfo> xarm() { return *robot_for_profile("xarm"); }

TEST(ServoArgs, ServoIdsAndNames) {
  EXPECT_EQ(*parse_servo("0", std::nullopt), 0);
  EXPECT_EQ(*parse_servo("255", std::nullopt), 255);
  EXPECT_EQ(parse_servo("256", std::nullopt).error().message, "servo must be 0..255, got 256");
  EXPECT_EQ(parse_servo("-1", std::nullopt).error().message, "servo must be 0..255, got -1");
  EXPECT_EQ(*parse_servo("base", xarm()), 6);
  EXPECT_EQ(parse_servo("hand", xarm()).error().message,
            "servo 'hand' is not a servo of the xarm profile (claw=1, wrist_roll=2, "
            "wrist_pitch=3, elbow=4, shoulder=5, base=6)");
  EXPECT_EQ(parse_servo("99999999999999999999", std::nullopt).error().message,
            "servo: '99999999999999999999' is far out of range");
}

TEST(ServoArgs, Targets) {
  // The text is parsed first; the range is checked_targets' business.
  EXPECT_EQ(*parse_target("2=65536", std::nullopt), (RequestedTarget{2, 65536}));
  EXPECT_EQ(*parse_target("claw=-3", xarm()), (RequestedTarget{1, -3}));
  EXPECT_EQ(parse_target("2=lots", std::nullopt).error().message,
            "position of servo 2: 'lots' is not a whole number");
  EXPECT_FALSE(parse_target("=5", std::nullopt));
  EXPECT_FALSE(parse_target("5=", std::nullopt));
}

TEST(ServoArgs, PositionRanges) {
  // A profile's servo: that profile's range (xarm 0..1000, lsc-6 500..2500).
  EXPECT_EQ(position_range(1, xarm()).min, 0);
  EXPECT_EQ(position_range(1, xarm()).max, 1000);
  auto lsc6 = *robot_for_profile("lsc-6");
  EXPECT_EQ(position_range(1, lsc6).min, 500);
  EXPECT_EQ(position_range(1, lsc6).max, 2500);
  // No profile: xarm/bus 0..1000 and lsc-16/32/6 500..2500 together, 0..2500.
  EXPECT_EQ(position_range(9, std::nullopt).min, 0);
  EXPECT_EQ(position_range(9, std::nullopt).max, 2500);
}

TEST(ServoArgs, CheckedTargets) {
  EXPECT_EQ(*checked_targets({{2, 2500}, {3, 0}}, std::nullopt),
            (std::vector<lsc::ServoTarget>{{2, 2500}, {3, 0}}));
  EXPECT_EQ(checked_targets({{1, 500}, {2, 2501}}, std::nullopt).error().message,
            "position of servo 2 must be 0..2500 on a servo controller (give --robot for a "
            "profile's own range), got 2501");
  EXPECT_EQ(checked_targets({{2, -1}}, std::nullopt).error().message,
            "position of servo 2 must be 0..2500 on a servo controller (give --robot for a "
            "profile's own range), got -1");
  // 0xff00 is the wire's "do not move": outside every range, so never sent as a position.
  EXPECT_FALSE(checked_targets({{2, 65280}}, std::nullopt));
  EXPECT_EQ(checked_targets({{1, 1001}}, xarm()).error().message,
            "position of servo 1 must be 0..1000 on xarm, got 1001");
  EXPECT_EQ(*checked_targets({{1, 0}, {6, 1000}}, xarm()),
            (std::vector<lsc::ServoTarget>{{1, 0}, {6, 1000}}));
  EXPECT_EQ(checked_targets({{1, 499}}, *robot_for_profile("lsc-6")).error().message,
            "position of servo 1 must be 500..2500 on lsc-6, got 499");
}

TEST(ServoArgs, Milliseconds) {
  EXPECT_EQ(*parse_milliseconds("1.5s", "--time"), 1500);
  EXPECT_EQ(*parse_milliseconds("65535ms", "--time"), 65535);
  EXPECT_EQ(parse_milliseconds("65536ms", "--time").error().message,
            "--time (ms) must be 0..65535, got 65536");
  EXPECT_EQ(parse_milliseconds("2b", "--time").error().message,
            "--time: beats need a tempo; give ms or s");
  EXPECT_FALSE(parse_milliseconds("500", "--time"));
}

TEST(ServoArgs, Groups) {
  EXPECT_EQ(*parse_group("0"), 0);
  EXPECT_EQ(*parse_group("254"), 254);
  EXPECT_FALSE(parse_group("255"));
  EXPECT_FALSE(parse_group("all"));
}

TEST(ServoArgs, ServoLists) {
  EXPECT_EQ(*parse_servo_list({"1", "elbow"}, xarm()), (std::vector<std::uint8_t>{1, 4}));
  EXPECT_EQ(parse_servo_list({"1", "claw"}, xarm()).error().message, "servo 1 is named twice");
  EXPECT_EQ(parse_servo_list({}, std::nullopt).error().message, "name at least one servo");
  EXPECT_EQ(parse_servo_list({"1", "claw"}, std::nullopt).error().message,
            "servo 'claw' is not an id; servo names need a profile, e.g. --robot xarm");
}

TEST(ServoArgs, TargetsOfOneMove) {
  EXPECT_EQ(*parse_targets({"2=300", "claw=0"}, xarm()),
            (std::vector<RequestedTarget>{{2, 300}, {1, 0}}));
  EXPECT_EQ(parse_targets({"1=300", "claw=0"}, xarm()).error().message, "servo 1 is named twice");
  const std::vector<std::string> many(256, "1=5");
  EXPECT_EQ(parse_targets(many, std::nullopt).error().message,
            "at most 255 servos fit in one move");
}

TEST(ServoArgs, Offsets) {
  // ServoOffsetRead reports a signed byte, so that is the range, though the request has a short.
  EXPECT_EQ(*parse_offset("-128"), -128);
  EXPECT_EQ(*parse_offset("127"), 127);
  EXPECT_EQ(*parse_offset("+5"), 5);
  EXPECT_EQ(parse_offset("128").error().message,
            "offset must be -128..127, got 128 (ServoOffsetRead reports offsets as a signed byte)");
  EXPECT_EQ(parse_offset("-129").error().message,
            "offset must be -128..127, got -129 (ServoOffsetRead reports offsets as a signed "
            "byte)");
  EXPECT_EQ(parse_offset("40000").error().message, "offset must be -32768..32767, got 40000");
  EXPECT_EQ(parse_offset("x").error().message, "offset: 'x' is not a whole number");
}

TEST(ServoArgs, GroupCommandArguments) {
  EXPECT_EQ(erase_target("3", false)->group, 3);
  EXPECT_TRUE(erase_target("", true)->all);
  EXPECT_EQ(erase_target("3", true).error().message, "give GROUP or --all, not both");
  EXPECT_EQ(erase_target("", false).error().message, "give a GROUP to erase, or --all");
  EXPECT_EQ(*run_times(3, true, false), 3);
  EXPECT_EQ(*run_times(1, false, true), 0);  // --forever is the wire's 0
  EXPECT_EQ(run_times(1, true, true).error().message, "give --times or --forever, not both");
  EXPECT_EQ(run_times(0, true, false).error().message,
            "--times must be 1..65535, got 0 (--forever loops until `seqc group stop`)");
  EXPECT_EQ(*parse_speed_percent("200"), 200);
  EXPECT_EQ(*parse_speed_percent("65535"), 65535);
  for (const char* bad : {"0", "65536", "12x", "", "-5"}) {
    EXPECT_EQ(parse_speed_percent(bad).error().message,
              "percent must be a whole number 1..65535 (100 = as stored), got '" +
                  std::string(bad) + "'");
  }
}

TEST(ServoArgs, Timeouts) {
  EXPECT_EQ(*parse_timeout("250ms"), std::chrono::milliseconds(250));
  EXPECT_EQ(*parse_timeout("2s"), std::chrono::seconds(2));
  EXPECT_EQ(parse_timeout("0ms").error().message,
            "--timeout must be more than 0 and at most 1 hour, got '0ms'");
  EXPECT_EQ(parse_timeout("2h").error().message,
            "--timeout: '2h' is not a time in ms or s; write it like '500ms' or '2s'");
  EXPECT_EQ(parse_timeout("4b").error().message,
            "--timeout: '4b' is not a time in ms or s; write it like '500ms' or '2s'");
}

}  // namespace
}  // namespace seqc::boards
