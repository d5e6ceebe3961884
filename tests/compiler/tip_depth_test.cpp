// The claw's tip against the table at every millisecond of a move of the arm's joints, on the
// xArm and the LeArm: moves whose deepest point is their midpoint (the wrist sweeping the hand
// through straight down while the shoulder and elbow stand still), with the depth, the instant
// and how long the tip is below worked out here by forward kinematics from the profiles' link
// lengths (not the compiler's); the same moves clear of the table say nothing.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <regex>
#include <string>
#include <vector>

#include "tests/compiler/lang_test_util.hpp"

namespace seqc::compiler {
namespace {

using testing::compile_text;
using testing::messages;

constexpr double kRad = std::numbers::pi / 180;

// "L:C warning: the tip goes D mm below the table at T s (deepest, [x, y, z]), for N ms".
struct Said {
  std::string where;
  double depth_mm = 0, at_s = 0, for_ms = 0;
  std::string point;
};

Said said(const std::string& message) {
  static const std::regex form(
      R"(^(\d+:\d+) warning: the tip goes ([0-9.]+) mm below the table at ([0-9.]+) s )"
      R"(\(deepest, (\[[^\]]*\])\), for (\d+) ms$)");
  std::smatch m;
  EXPECT_TRUE(std::regex_match(message, m, form)) << message;
  if (m.empty()) return {};
  return {m[1], std::stod(m[2]), std::stod(m[3]), std::stod(m[5]), m[4]};
}

// The xArm: 0.24 degrees per unit, shoulder, elbow and wrist each at -(position - 500) * 0.24;
// links 72 (table to shoulder), 97, 96 and 150 mm. Shoulder 328 and elbow 297 are s = 41.28
// and e = 48.72 degrees, so the forearm is level (s + e = 90); the wrist from 25 to 225 (w = 114
// to 66 degrees) sweeps the hand through straight down (s + e + w = 180) at its midpoint, 125,
// where the tip is lowest: z = 72 + 97 cos s + 96 cos 90 + 150 cos 180.
std::string xarm_sweep(int shoulder, const std::string& move_keys) {
  return "robot: xarm\nsequence:\n  - move: home\n    time: 1s\n"
         "  - move: {shoulder: " +
         std::to_string(shoulder) +
         ", elbow: 297, wrist_pitch: 25}\n    time: 1s\n"
         "  - move: {wrist_pitch: 225}\n" +
         move_keys;
}

TEST(TipDepth, XarmJointMoveThroughTheTableSaysHowDeepAndWhen) {
  const double s = 41.28 * kRad;
  const double z = 72 + 97 * std::cos(s) + 96 * std::cos(90 * kRad) + 150 * std::cos(180 * kRad);
  EXPECT_NEAR(z, -5.105, 0.001);
  // r = 97 sin s + 96 sin 90 + 150 sin 180 = 64.0 + 96 = 160 mm in front of the base.
  // Below the table while |s + e + w - 180| < acos((72 + 97 cos s) / 150): the hand turns 48
  // degrees in the move's 1000 ms.
  const double below_ms = 2 * std::acos((72 + 97 * std::cos(s)) / 150) / kRad / 48 * 1000;
  EXPECT_NEAR(below_ms, 624.6, 0.1);
  const std::vector<std::string> got = messages(compile_text(xarm_sweep(328, "    time: 1s\n")));
  ASSERT_EQ(got.size(), 1u) << ::testing::PrintToString(got);
  const Said d = said(got[0]);
  EXPECT_EQ(d.where, "7:5");  // the move's step
  EXPECT_NEAR(d.depth_mm, -z, 0.1);
  EXPECT_NEAR(d.at_s, 2.5, 0.001);  // home 1 s, to the start 1 s, then half of the sweep
  EXPECT_NEAR(d.for_ms, below_ms, 2);
  EXPECT_EQ(d.point, "[160mm, 0mm, -5mm]");
}

TEST(TipDepth, XarmEasedAndLongMovesAreCheckedAlike) {
  // in-out is symmetric about its midpoint, which it reaches at half the time: the same lowest
  // point at the same instant, below the table for less time (the middle goes fastest).
  const double s = 41.28 * kRad;
  const double depth = -(72 + 97 * std::cos(s) - 150);
  const std::vector<std::string> eased =
      messages(compile_text(xarm_sweep(328, "    time: 1s\n    ease: in-out\n")));
  ASSERT_EQ(eased.size(), 1u) << ::testing::PrintToString(eased);
  EXPECT_NEAR(said(eased[0]).depth_mm, depth, 0.1);
  EXPECT_NEAR(said(eased[0]).at_s, 2.5, 0.001);
  EXPECT_LT(said(eased[0]).for_ms, 625);
  // A minute-long sweep is sampled every 6 ms (10,000 instants), each counted lower by half the
  // spacing times the wrist's speed times the hand: 3 ms * (200 * 0.24 / 60000 degrees/ms, in
  // radians) * 150 mm = 0.0063 mm. Where the tip crosses the table it sinks 150 sin 15 degrees
  // times that speed, 0.00054 mm/ms, so the margin counts about 12 ms more at either crossing.
  const std::vector<std::string> slow = messages(compile_text(xarm_sweep(328, "    time: 60s\n")));
  ASSERT_EQ(slow.size(), 1u) << ::testing::PrintToString(slow);
  EXPECT_NEAR(said(slow[0]).depth_mm, depth, 0.1);
  EXPECT_NEAR(said(slow[0]).at_s, 2 + 30, 0.006);
  EXPECT_NEAR(said(slow[0]).for_ms, 60 * 624.6 + 2 * 12, 12);
}

TEST(TipDepth, XarmMoveAboveTheTableSaysNothing) {
  // Shoulder 340 (s = 38.4 degrees, the forearm 2.88 degrees above level): at the sweep's
  // midpoint z = 72 + 97 cos 38.4 + 96 cos 87.12 - 150 = 2.8 mm, its lowest.
  const double s = 38.4 * kRad;
  EXPECT_NEAR(72 + 97 * std::cos(s) + 96 * std::cos(87.12 * kRad) - 150, 2.8, 0.1);
  EXPECT_TRUE(messages(compile_text(xarm_sweep(340, "    time: 1s\n"))).empty());
}

// The LeArm: 0.09 degrees per microsecond, the shoulder at +(position - 1500) * 0.09 and the
// elbow and wrist at -(position - 1500) * 0.09; links 85, 104.3, 89 and 177 mm. Shoulder 1590
// and elbow 500 are s = 8.1 and e = 90 degrees; the wrist from 680 to 500 (w = 73.8 to 90)
// sweeps the hand through straight down at its midpoint, 590 (w = 81.9, s + e + w = 180).
std::string learm_sweep(int shoulder) {
  return "robot: learm\nsequence:\n  - move: home\n    time: 1s\n"
         "  - move: {shoulder: " +
         std::to_string(shoulder) +
         ", elbow: 500, wrist_pitch: 680}\n    time: 1s\n"
         "  - move: {wrist_pitch: 500}\n    time: 1s\n";
}

TEST(TipDepth, LearmJointMoveThroughTheTableSaysHowDeepAndWhen) {
  const double s = 8.1 * kRad;
  const double z =
      85 + 104.3 * std::cos(s) + 89 * std::cos(98.1 * kRad) + 177 * std::cos(180 * kRad);
  EXPECT_NEAR(z, -1.281, 0.001);
  // The hand turns 16.2 degrees in 1000 ms.
  const double below_ms = 2 *
                          std::acos((85 + 104.3 * std::cos(s) + 89 * std::cos(98.1 * kRad)) / 177) /
                          kRad / 16.2 * 1000;
  const std::vector<std::string> got = messages(compile_text(learm_sweep(1590)));
  ASSERT_EQ(got.size(), 1u) << ::testing::PrintToString(got);
  const Said d = said(got[0]);
  EXPECT_EQ(d.where, "7:5");
  EXPECT_NEAR(d.depth_mm, -z, 0.1);
  EXPECT_NEAR(d.at_s, 2.5, 0.001);
  EXPECT_NEAR(d.for_ms, below_ms, 2);
  // r = 104.3 sin 8.1 + 89 sin 98.1 + 177 sin 180 = 14.7 + 88.1 = 102.8 mm.
  EXPECT_EQ(d.point, "[103mm, 0mm, -1mm]");
}

TEST(TipDepth, LearmMoveAboveTheTableSaysNothing) {
  // Shoulder 1560, s = 5.4 degrees: z = 85 + 104.3 cos 5.4 + 89 cos 95.4 - 177 = 3.5 mm at the
  // midpoint.
  EXPECT_NEAR(85 + 104.3 * std::cos(5.4 * kRad) + 89 * std::cos(95.4 * kRad) - 177, 3.5, 0.1);
  EXPECT_TRUE(messages(compile_text(learm_sweep(1560))).empty());
}

TEST(TipDepth, TipMoveBetweenTwoPointsAboveTheTableIsCheckedBetweenThem) {
  // Both ends 4 mm above the table; the joints' own curves between them take the claw through it.
  const std::vector<std::string> got = messages(compile_text(R"(robot: xarm
sequence:
  - move: home
    time: 1s
  - move: {tip: [120mm, 0mm, 4mm], pitch: 160deg}
    time: 1s
  - move: {tip: [240mm, 0mm, 4mm], pitch: 100deg}
    time: 1s
)"));
  ASSERT_EQ(got.size(), 1u) << ::testing::PrintToString(got);
  const Said d = said(got[0]);
  EXPECT_EQ(d.where, "7:5");
  EXPECT_GT(d.depth_mm, 4);
  EXPECT_GT(d.at_s, 2);
  EXPECT_LT(d.at_s, 3);
}

}  // namespace
}  // namespace seqc::compiler
