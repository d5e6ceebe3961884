// Moving the xArm's tip in millimetres: the joint positions a `tip:` move compiles to, checked
// by forward kinematics written out here from the documented conventions (not the compiler's),
// and the wording of the moves it refuses.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <string>

#include "tests/compiler/lang_test_util.hpp"
#include "tests/compiler/xarm_reference.hpp"

namespace seqc::compiler {
namespace {

using testing::compile_text;
using testing::distance;
using testing::kDegPerUnit;
using testing::messages;
using testing::program_of;

// An arm as the documents give it: ids claw 1 .. base 6 (wrist pitch 3, elbow 4, shoulder 5),
// degrees per unit, every joint's zero, each joint's sign and the link lengths in mm.
struct WrittenArm {
  double deg_per_unit, zero;
  int base_sign, shoulder_sign, elbow_sign, wrist_sign;
  double base_height, upper, fore, hand;
};

// The xArm profile: 1000 units over 240 degrees (kDegPerUnit); links 72 (table to shoulder),
// 97, 96 and 150 mm; every joint's zero at 500, the base turning +1, the others -1.
constexpr WrittenArm kXarm = {kDegPerUnit, 500, 1, -1, -1, -1, 72, 97, 96, 150};

// Each servo's last commanded position, by bus id.
std::map<int, int> final_positions(const ServoProgram& p) {
  std::map<int, int> out;
  for (const Keyframe& k : p.keyframes) {
    for (const auto& t : k.targets) out[t.id] = t.position;
  }
  return out;
}

struct Tip {
  std::array<double, 3> at;
  double pitch;  // degrees
  // How far rounding each joint by half a unit can move the tip (first order: the angle times
  // the joint's distance to the tip in this pose, summed over the joints).
  double rounding_mm;
};

// r = U sin s + F sin(s+e) + H sin(s+e+w), z = base_height + U cos s + F cos(s+e) + H cos(s+e+w),
// x = r cos(base), y = r sin(base).
Tip forward(std::map<int, int> pos, const WrittenArm& a = kXarm) {
  const double rad = std::numbers::pi / 180;
  auto angle = [&](int id, int sign) { return sign * (pos[id] - a.zero) * a.deg_per_unit * rad; };
  const double base = angle(6, a.base_sign);
  const double s = angle(5, a.shoulder_sign);
  const double e = angle(4, a.elbow_sign);
  const double w = angle(3, a.wrist_sign);
  const double r = a.upper * std::sin(s) + a.fore * std::sin(s + e) + a.hand * std::sin(s + e + w);
  const double z = a.base_height + a.upper * std::cos(s) + a.fore * std::cos(s + e) +
                   a.hand * std::cos(s + e + w);
  // In the arm's plane, the shoulder at (0, base_height), the elbow and the wrist after it.
  const double elbow_r = a.upper * std::sin(s), elbow_z = a.base_height + a.upper * std::cos(s);
  const double half_unit = 0.5 * a.deg_per_unit * rad;
  const double reach = std::abs(r) + std::hypot(r, z - a.base_height) +
                       std::hypot(r - elbow_r, z - elbow_z) + a.hand;
  // 0.01 mm covers the second-order terms (about the reach times the angle squared).
  return {{r * std::cos(base), r * std::sin(base), z}, (s + e + w) / rad, half_unit * reach + 0.01};
}

// Rounding a joint to whole units moves it by at most half a unit, 0.12 degrees; the tip moves
// by at most that angle times the joint's distance to the tip (Tip::rounding_mm), never more
// than with each distance at its longest, the links beyond the joint: base and shoulder
// 97+96+150, elbow 96+150, wrist 150 mm, about 2.3 mm. The IK itself is exact.
const double kRoundingMm =
    0.5 * kDegPerUnit * std::numbers::pi / 180 * ((343 + 343) + (96 + 150) + 150);
constexpr double kRoundingPitch = 3 * 0.5 * kDegPerUnit;  // shoulder, elbow and wrist

const ServoProgram& compiled(const CompileOutput& out) { return program_of(out); }

TEST(ArmTip, AbsoluteTipIsReachedWithinRounding) {
  const auto out = compile_text(R"(robot: xarm
sequence:
  - move: home
    time: 1s
  - move: {tip: [200mm, 0mm, 50mm], pitch: 135deg, claw: 300}
    time: 1s
)");
  const std::map<int, int> pos = final_positions(compiled(out));
  const Tip tip = forward(pos);
  EXPECT_LE(distance(tip.at, {200, 0, 50}), tip.rounding_mm);
  EXPECT_LT(tip.rounding_mm, kRoundingMm);
  EXPECT_NEAR(tip.pitch, 135, kRoundingPitch);
  EXPECT_EQ(pos.at(6), 500);  // straight along +x: the base at its zero
  EXPECT_EQ(pos.at(1), 300);  // the claw moves in the same step
}

TEST(ArmTip, BaseFacesThePoint) {
  // (0, 100) is 90 degrees counter-clockwise from +x: 500 + 90 / 0.24 = 875.
  const auto out = compile_text(R"(robot: xarm
sequence:
  - move: home
    time: 1s
  - move: {tip: [0mm, 200mm, 50mm], pitch: 135deg}
    time: 1s
)");
  const std::map<int, int> pos = final_positions(compiled(out));
  EXPECT_EQ(pos.at(6), 875);
  EXPECT_LE(distance(forward(pos).at, {0, 200, 50}), forward(pos).rounding_mm);
}

TEST(ArmTip, ElbowDownIsTheOtherSolution) {
  const std::string move =
      "robot: xarm\nsequence:\n  - move: home\n    time: 1s\n"
      "  - move: {tip: [250mm, 0mm, 80mm], pitch: 135deg}\n    time: 1s\n";
  const auto up = compile_text(move);
  const auto down = compile_text(move + "    elbow: down\n");
  const std::map<int, int> up_pos = final_positions(compiled(up));
  const std::map<int, int> down_pos = final_positions(compiled(down));
  // Elbow up bends the forearm forwards (a positive elbow angle: a position below 500), down
  // bends it back; both put the tip at the same point.
  EXPECT_LT(up_pos.at(4), 500);
  EXPECT_GT(down_pos.at(4), 500);
  EXPECT_LE(distance(forward(up_pos).at, {250, 0, 80}), forward(up_pos).rounding_mm);
  EXPECT_LE(distance(forward(down_pos).at, {250, 0, 80}), forward(down_pos).rounding_mm);
  EXPECT_NEAR(forward(down_pos).pitch, 135, kRoundingPitch);
}

TEST(ArmTip, ElbowMayBeChosenInsideTheMove) {
  // In a tip move the elbow's servo is placed by the tip, so `elbow: down` inside the move
  // chooses the solution exactly as the step's key does.
  const std::string head = "robot: xarm\nsequence:\n  - move: home\n    time: 1s\n";
  const auto beside =
      compile_text(head +
                   "  - move: {tip: [250mm, 0mm, 80mm], pitch: 135deg}\n    time: 1s\n"
                   "    elbow: down\n");
  const auto inside = compile_text(
      head + "  - move: {tip: [250mm, 0mm, 80mm], pitch: 135deg, elbow: down}\n    time: 1s\n");
  const std::map<int, int> pos = final_positions(compiled(inside));
  EXPECT_GT(pos.at(4), 500);
  EXPECT_EQ(pos, final_positions(compiled(beside)));

  const auto twice = compile_text(head +
                                  "  - move: {tip: [250mm, 0mm, 80mm], elbow: down}\n    time: 1s\n"
                                  "    elbow: up\n");
  EXPECT_EQ(messages(twice),
            std::vector<std::string>{
                "5:44 error: 'elbow' is given twice, in the move and beside it; keep one"});
  // A number is still the elbow's servo, which the tip places.
  const auto servo =
      compile_text(head + "  - move: {tip: [250mm, 0mm, 80mm], elbow: 300}\n    time: 1s\n");
  EXPECT_EQ(messages(servo),
            std::vector<std::string>{"5:44 error: 'elbow' is placed by 'tip' in this move; "
                                     "leave it out or drop 'tip'"});
}

// [150mm, -80mm, 40mm] reads like an absolute point on the right, but the sign makes it an
// offset: an unsigned coordinate that is not 0 beside a signed one is warned about.
TEST(ArmTip, AnUnsignedCoordinateInARelativeTipIsWarnedAbout) {
  const std::string head =
      "robot: xarm\nsequence:\n  - move: home\n    time: 1s\n"
      "  - move: {tip: [200mm, 0mm, 100mm], pitch: 135deg}\n    time: 1s\n";
  EXPECT_EQ(messages(compile_text(head + "  - move: {tip: [+20mm, 0mm, 5mm]}\n    time: 1s\n")),
            std::vector<std::string>{
                "7:30 warning: '5mm' has no sign, but a sign elsewhere in this tip makes the "
                "whole point relative, so it moves the tip by 5mm too; write '+5mm', or name "
                "the coordinates for an absolute point: 'tip: {x: +20mm, y: 0mm, z: 5mm}'"});
  // 0mm beside a sign is "no change", as documented: no warning.
  EXPECT_TRUE(
      messages(compile_text(head + "  - move: {tip: [+20mm, 0mm, -5mm]}\n    time: 1s\n")).empty());
}

TEST(ArmTip, SignedTipMovesFromTheCurrentTipAndKeepsThePitch) {
  const auto out = compile_text(R"(robot: xarm
sequence:
  - move: home
    time: 1s
  - move: {tip: [200mm, 0mm, 50mm], pitch: 135deg}
    time: 1s
  - move: {tip: [0mm, 0mm, +60mm]}
    time: 1s
)");
  const ServoProgram& p = compiled(out);
  std::map<int, int> before;
  for (const Keyframe& k : p.keyframes) {
    if (k.start_ms >= 2000) break;
    for (const auto& t : k.targets) before[t.id] = t.position;
  }
  const Tip from = forward(before);
  const Tip to = forward(final_positions(p));
  // Relative to where the rounded joints put the tip, so only the second rounding counts.
  EXPECT_LE(distance(to.at, {from.at[0], from.at[1], from.at[2] + 60}), to.rounding_mm);
  EXPECT_NEAR(to.pitch, from.pitch, kRoundingPitch);
}

TEST(ArmTip, RefusedMovesSayWhy) {
  // The wrist is 150 mm above the tip when the hand points down: at r = 150, z = 80 + 150 - 72 =
  // 158 from the shoulder, hypot(150, 158) = 217.9 mm, 24.9 beyond 97 + 96 = 193.
  EXPECT_EQ(messages(compile_text(R"(robot: xarm
sequence:
  - move: home
    time: 1s
  - move: {tip: [150mm, 0mm, 80mm], pitch: 180deg}
    time: 1s
)")),
            std::vector<std::string>{
                "5:17 error: the tip [150mm, 0mm, 80mm] at pitch 180deg is 25 mm beyond the arm's "
                "reach of 193 mm (the wrist, 150 mm back from the tip, is 218 mm from the "
                "shoulder)"});
  // Pointing down at r = 30: wrist (30, 158), elbow acos((160.82^2 - 97^2 - 96^2) / (2 97 96))
  // = 67.13deg, shoulder atan2(30, 158) - atan2(96 sin e, 97 + 96 cos e) = -22.62deg, wrist
  // 180 + 22.62 - 67.13 = 135.49deg: 500 - 135.49 / 0.24 = -64.5, below the servo's 0.
  EXPECT_EQ(messages(compile_text(R"(robot: xarm
sequence:
  - move: home
    time: 1s
  - move: {tip: [30mm, 0mm, 80mm], pitch: 180deg}
    time: 1s
)")),
            std::vector<std::string>{
                "5:17 error: the tip [30mm, 0mm, 80mm] at pitch 180deg needs 'wrist_pitch' at -65 "
                "(135.5deg), 65 below its min 0"});
  // Home stands the arm straight up, the tip at 72 + 97 + 96 + 150 = 415 mm; 420 mm down is 5
  // mm under the table.
  EXPECT_EQ(messages(compile_text(R"(robot: xarm
sequence:
  - move: home
    time: 1s
  - move: {tip: [0mm, 0mm, -420mm]}
    time: 1s
)")),
            std::vector<std::string>{
                "5:17 error: the tip [0mm, 0mm, -5mm] would be 5 mm below the table"});
  EXPECT_EQ(messages(compile_text(R"(robot: lsc-16
sequence:
  - move: {tip: [200mm, 0mm, 50mm]}
    time: 1s
)")),
            std::vector<std::string>{
                "3:17 error: 'tip' needs the arm's geometry, and robot 'lsc-16' has none; give it "
                "with 'robot: {arm: ...}'"});
  EXPECT_EQ(messages(compile_text(R"(robot: xarm
sequence:
  - move: {tip: [+20mm, 0mm, 0mm]}
    time: 1s
)")),
            std::vector<std::string>{
                "3:17 error: 'base' has no known position yet, so the tip's position is unknown; "
                "move the arm to absolute positions first"});
}

TEST(ArmTip, NamedTipIsAbsoluteWithNegativeCoordinates) {
  // y = -80 is to the right: the base turns atan2(-80, 150) = -28.07 degrees, 500 - 28.07 / 0.24
  // = 383.04, so 383; with pitch 135 the point is reached within rounding.
  const auto out = compile_text(R"(robot: xarm
sequence:
  - move: home
    time: 1s
  - move: {tip: {x: 150mm, y: -80mm, z: 40mm}, pitch: 135deg}
    time: 1s
)");
  ASSERT_TRUE(messages(out).empty()) << ::testing::PrintToString(messages(out));
  const std::map<int, int> pos = final_positions(compiled(out));
  EXPECT_EQ(pos.at(6), 383);
  EXPECT_LE(distance(forward(pos).at, {150, -80, 40}), forward(pos).rounding_mm);
  // The same point in the list form is relative (a sign makes it so): from home's tip at
  // [0, 0, 415] it would be [150, -80, 455], out of reach, so the forms differ.
  EXPECT_FALSE(messages(compile_text(R"(robot: xarm
sequence:
  - move: home
    time: 1s
  - move: {tip: [150mm, -80mm, 40mm], pitch: 135deg}
    time: 1s
)"))
                   .empty());
}

TEST(ArmTip, NamedTipNamesItsMistakes) {
  EXPECT_EQ(messages(compile_text(R"(robot: xarm
sequence:
  - move: home
    time: 1s
  - move: {tip: {x: 150mm, yy: -80mm, z: 40mm}, pitch: 135deg}
    time: 1s
)")),
            (std::vector<std::string>{
                "5:28 error: unknown key 'yy' in 'tip'; did you mean 'y'?",
                "5:17 error: 'tip' needs 'y' as well, e.g. 'tip: {x: 150mm, y: -80mm, z: 40mm}'"}));
}

// The LeArm's built-in geometry: 2000 us over 180 degrees, zeros at 1500; the base and the
// shoulder turn +1 and the elbow and wrist -1; links 85 (table to shoulder), 104.3, 89, 177 mm.
TEST(ArmTip, LearmTipIsReachedWithItsOwnSignsAndUnits) {
  const auto out = compile_text(R"(robot: learm
sequence:
  - move: home
    time: 1s
  - move: {tip: [120mm, 90mm, 60mm], pitch: 150deg}
    time: 1s
)");
  std::map<int, int> pos = final_positions(compiled(out));
  const double per = 0.09;
  const Tip tip = forward(pos, {per, 1500, 1, 1, -1, -1, 85, 104.3, 89, 177});
  // Half a unit is 0.045 degrees, at most (370.3 + 370.3 + 266 + 177) mm from the tip.
  EXPECT_LE(distance(tip.at, {120, 90, 60}), tip.rounding_mm);
  EXPECT_LT(tip.rounding_mm, 0.5 * per * std::numbers::pi / 180 * (370.3 + 370.3 + 266 + 177));
  EXPECT_NEAR(tip.pitch, 150, 3 * 0.5 * per);
  // atan2(90, 120) = 36.87 degrees counter-clockwise: 1500 + 36.87 / 0.09 = 1909.7 us.
  EXPECT_NEAR(pos[6], 1910, 1);
}

// A point that whole units reach exactly leaves no rounding: the tip lands on it within the
// thousandth of a millimetre it is written to, so every link length shows. Shoulder 400, elbow
// 200 and wrist 300 (each angle -(position - 500) * 0.24 degrees) are s = 24, e = 72 and w = 48
// degrees, pitch 144; r = 97 sin 24 + 96 sin 96 + 150 sin 144 = 39.453 + 95.474 + 88.168 = 223.095
// and z = 72 + 97 cos 24 + 96 cos 96 + 150 cos 144 = 72 + 88.614 - 10.035 - 121.353 = 29.227 mm.
// With the upper arm and the forearm swapped (96 and 97 mm) the same point needs shoulder 402
// and wrist 298, which put the tip 1.3 mm from it: far beyond this test's 0.01 mm.
TEST(ArmTip, EachLinkLengthMovesTheTip) {
  const auto out = compile_text(R"(robot: xarm
sequence:
  - move: home
    time: 1s
  - move: {tip: [223.095mm, 0mm, 29.227mm], pitch: 144deg}
    time: 1s
)");
  const std::map<int, int> pos = final_positions(compiled(out));
  const double rad = std::numbers::pi / 180;
  const double s = 24 * rad, e = 72 * rad, w = 48 * rad;
  const std::array<double, 3> written = {
      97 * std::sin(s) + 96 * std::sin(s + e) + 150 * std::sin(s + e + w), 0,
      72 + 97 * std::cos(s) + 96 * std::cos(s + e) + 150 * std::cos(s + e + w)};
  EXPECT_NEAR(written[0], 223.095, 0.0005);
  EXPECT_NEAR(written[2], 29.227, 0.0005);
  EXPECT_EQ(pos.at(5), 400);
  EXPECT_EQ(pos.at(4), 200);
  EXPECT_EQ(pos.at(3), 300);
  EXPECT_LE(distance(forward(pos).at, written), 0.01);
  // What the swap would compile to is 1.3 mm off by the true lengths.
  EXPECT_GT(distance(forward({{6, 500}, {5, 402}, {4, 200}, {3, 298}}).at, written), 1.0);
}

}  // namespace
}  // namespace seqc::compiler
