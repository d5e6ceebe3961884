// The arm's geometry: the xArm's built-in numbers, the file's `arm:` overrides and their
// located errors, the forward kinematics and simulate's tip columns. Every expected tip is the
// formula written out here: with U, F, H the upper arm, forearm and hand and s, e, w the
// shoulder, elbow and wrist angles (each sign * (position - zero) * 0.24 degrees on the xArm),
//   r = U sin s + F sin(s+e) + H sin(s+e+w), z = 72 + U cos s + F cos(s+e) + H cos(s+e+w),
//   x = r cos(base), y = r sin(base).
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numbers>
#include <string>

#include "compiler/compile.hpp"
#include "compiler/formats/simulate.hpp"
#include "compiler/program/arm_kinematics.hpp"
#include "tests/compiler/lang_test_util.hpp"

namespace seqc::compiler {
namespace {

using compiler::testing::compile_text;
using compiler::testing::diagnostics_of;
using compiler::testing::messages;
using compiler::testing::program_of;

constexpr double kDeg = std::numbers::pi / 180;

// The xArm's geometry as a program carries it.
compiler::ArmGeometry xarm() {
  const auto out = compile_text("robot: xarm\nsequence:\n  - move: {claw: 600}\n    time: 1s\n");
  const compiler::ServoProgram& p = program_of(out);
  EXPECT_TRUE(p.robot.arm.has_value());
  return p.robot.arm.value_or(compiler::ArmGeometry{});
}

// The tip for positions given by servo name (the rest at 500).
std::array<double, 3> tip(const compiler::ArmGeometry& arm,
                          const std::map<std::string, double>& positions) {
  return arm_points(arm,
                    [&](std::string_view name) {
                      auto it = positions.find(std::string(name));
                      return it == positions.end() ? 500.0 : it->second;
                    })
      .tip;
}

void expect_tip(const std::array<double, 3>& got, double x, double y, double z) {
  EXPECT_NEAR(got[0], x, 1e-9);
  EXPECT_NEAR(got[1], y, 1e-9);
  EXPECT_NEAR(got[2], z, 1e-9);
}

TEST(ArmGeometry, XarmHasTheBuiltInNumbers) {
  const compiler::ArmGeometry arm = xarm();
  EXPECT_EQ(arm.base_height, 72);
  EXPECT_EQ(arm.upper_arm, 97);
  EXPECT_EQ(arm.forearm, 96);
  EXPECT_EQ(arm.hand, 150);
  EXPECT_EQ(arm.base, (compiler::ArmJoint{"base", 500, 1}));
  EXPECT_EQ(arm.shoulder, (compiler::ArmJoint{"shoulder", 500, -1}));
  EXPECT_EQ(arm.elbow, (compiler::ArmJoint{"elbow", 500, -1}));
  EXPECT_EQ(arm.wrist, (compiler::ArmJoint{"wrist_pitch", 500, -1}));
  EXPECT_EQ(arm.claw, "claw");
  EXPECT_DOUBLE_EQ(arm.degrees_per_unit, 240.0 / 1000.0);  // LX-15D: 1000 units over 240 deg
}

// The LeArm's: Hiwonder's firmware lengths (104.3, 89, 177 mm), a measured 85 mm base, PWM
// units (2000 us over 180 deg, so 0.09 deg per unit) and joints at zero at 1500 us.
TEST(ArmGeometry, LearmHasTheBuiltInNumbers) {
  const auto out = compile_text("robot: learm\nsequence:\n  - move: {claw: 1600}\n    time: 1s\n");
  const compiler::ServoProgram& p = program_of(out);
  ASSERT_TRUE(p.robot.arm.has_value()) << diagnostics_of(out);
  const compiler::ArmGeometry& arm = *p.robot.arm;
  EXPECT_EQ(arm.base_height, 85);
  EXPECT_EQ(arm.upper_arm, 104.3);
  EXPECT_EQ(arm.forearm, 89);
  EXPECT_EQ(arm.hand, 177);
  EXPECT_EQ(arm.base, (compiler::ArmJoint{"base", 1500, 1}));
  EXPECT_EQ(arm.shoulder, (compiler::ArmJoint{"shoulder", 1500, 1}));
  EXPECT_EQ(arm.elbow, (compiler::ArmJoint{"elbow", 1500, -1}));
  EXPECT_EQ(arm.wrist, (compiler::ArmJoint{"wrist_pitch", 1500, -1}));
  EXPECT_EQ(arm.claw, "claw");
  EXPECT_DOUBLE_EQ(arm.degrees_per_unit, 180.0 / 2000.0);
  EXPECT_EQ(p.robot.board, "lsc6");  // uploads in the LSC-6 board's dialect
  EXPECT_EQ(p.robot.servos.size(), 6u);

  auto at = [&](const std::map<std::string, double>& positions) {
    return arm_points(arm,
                      [&](std::string_view name) {
                        auto it = positions.find(std::string(name));
                        return it == positions.end() ? 1500.0 : it->second;
                      })
        .tip;
  };
  expect_tip(at({}), 0, 0, 85 + 104.3 + 89 + 177);
  // The firmware's reset pose (servos 3, 4, 5 at 644, 511, 1255 us), by the formula: s =
  // (1255 - 1500) x 0.09 = -22.05 deg, e = -(511 - 1500) x 0.09 = 89.01 deg, w = -(644 - 1500) x
  // 0.09 = 77.04 deg.
  const double s = -22.05 * kDeg, e = 89.01 * kDeg, w = 77.04 * kDeg;
  const double r = 104.3 * std::sin(s) + 89 * std::sin(s + e) + 177 * std::sin(s + e + w);
  const double z = 85 + 104.3 * std::cos(s) + 89 * std::cos(s + e) + 177 * std::cos(s + e + w);
  const auto reset = at({{"wrist_pitch", 644}, {"elbow", 511}, {"shoulder", 1255}});
  expect_tip(reset, r, 0, z);
  // The firmware gives that pose as the point 150 mm out and 20 mm above its origin, which is
  // 28.9 mm below the shoulder: the signs above put the tip there within a few millimetres
  // (its pulses are rounded to whole microseconds and its own lengths to tenths of a mm).
  EXPECT_NEAR(reset[0], 150, 4);
  EXPECT_NEAR(reset[2], 20 + (85 - 28.9), 4);
}

TEST(ArmGeometry, AllAnglesZeroPointsStraightUp) {
  expect_tip(tip(xarm(), {}), 0, 0, 72 + 97 + 96 + 150);
}

TEST(ArmGeometry, ShoulderAtNinetyDegreesLaysTheArmFlat) {
  // 90 deg = 375 units; the shoulder's sign is -1, so position 500 - 375.
  expect_tip(tip(xarm(), {{"shoulder", 125}}), 97 + 96 + 150, 0, 72);
  // The base a quarter turn counter-clockwise (500 + 375) points it along +y.
  expect_tip(tip(xarm(), {{"shoulder", 125}, {"base", 875}}), 0, 343, 72);
  // Clockwise (500 - 375): along -y.
  expect_tip(tip(xarm(), {{"shoulder", 125}, {"base", 125}}), 0, -343, 72);
}

TEST(ArmGeometry, ElbowAndWristAddToTheAnglesBefore) {
  // Elbow 90 deg: the forearm and hand lie flat at the elbow's height.
  expect_tip(tip(xarm(), {{"elbow", 125}}), 96 + 150, 0, 72 + 97);
  // Wrist -90 deg (position 500 + 375): the hand points back over the base.
  expect_tip(tip(xarm(), {{"wrist_pitch", 875}}), -150, 0, 72 + 97 + 96);
}

TEST(ArmGeometry, AGeneralPoseFollowsTheFormula) {
  // shoulder 30 deg, elbow 45 deg, wrist -60 deg, base -20 deg, in units of 0.24 deg.
  const double s = 30 * kDeg, e = 45 * kDeg, w = -60 * kDeg, b = -20 * kDeg;
  const double r = 97 * std::sin(s) + 96 * std::sin(s + e) + 150 * std::sin(s + e + w);
  const double z = 72 + 97 * std::cos(s) + 96 * std::cos(s + e) + 150 * std::cos(s + e + w);
  expect_tip(tip(xarm(), {{"shoulder", 500 - 30 / 0.24},
                          {"elbow", 500 - 45 / 0.24},
                          {"wrist_pitch", 500 + 60 / 0.24},
                          {"base", 500 - 20 / 0.24}}),
             r * std::cos(b), r * std::sin(b), z);
}

TEST(ArmGeometry, TheFileOverridesLengthsAndJoints) {
  const auto out = compile_text(R"(robot:
  profile: xarm
  arm:
    hand: 120mm
    base_height: 80
    joints:
      wrist: {servo: wrist_roll, sign: 1}
      shoulder: {zero: 400}
sequence:
  - move: {claw: 600}
    time: 1s
)");
  const compiler::ServoProgram& p = program_of(out);
  ASSERT_TRUE(p.robot.arm.has_value());
  const compiler::ArmGeometry& arm = *p.robot.arm;
  EXPECT_EQ(arm.hand, 120);
  EXPECT_EQ(arm.base_height, 80);
  EXPECT_EQ(arm.upper_arm, 97);  // kept
  EXPECT_EQ(arm.wrist, (compiler::ArmJoint{"wrist_roll", 500, 1}));
  EXPECT_EQ(arm.shoulder, (compiler::ArmJoint{"shoulder", 400, -1}));
  // Shoulder at 400 is its zero now: 500 there is -24 deg (sign -1), tilting back.
  const double s = -24 * kDeg;
  expect_tip(tip(arm, {{"shoulder", 500}}), (97 + 96 + 120) * std::sin(s), 0,
             80 + (97 + 96 + 120) * std::cos(s));
}

TEST(ArmGeometry, ARenamedServoKeepsItsJoint) {
  const auto out = compile_text(R"(robot:
  profile: xarm
  servos:
    lift: 5
sequence:
  - move: {lift: 125}
    time: 1s
)");
  const compiler::ServoProgram& p = program_of(out);
  ASSERT_TRUE(p.robot.arm.has_value());
  EXPECT_EQ(p.robot.arm->shoulder.servo, "lift");
}

TEST(ArmGeometry, MistakesInArmAreLocated) {
  const auto out = compile_text(R"(robot:
  profile: xarm
  arm:
    hnad: 120
    forearm: -3
    joints:
      wrist: {servo: wrist_pich, sign: 2}
      knee: {servo: elbow}
sequence:
  - move: {claw: 600}
    time: 1s
)");
  EXPECT_EQ(out.servo_program(), nullptr);
  const std::string all = diagnostics_of(out);
  const std::vector<std::string> m = messages(out);
  ASSERT_EQ(m.size(), 5u) << all;
  EXPECT_EQ(m[0].rfind("4:5 error: ", 0), 0u) << m[0];
  EXPECT_NE(m[0].find("'hnad'"), std::string::npos) << m[0];
  EXPECT_NE(m[0].find("did you mean 'hand'"), std::string::npos) << m[0];
  EXPECT_EQ(m[1].rfind("5:14 error: 'forearm' must be a length in mm", 0), 0u) << m[1];
  EXPECT_EQ(m[2].rfind("8:7 error: ", 0), 0u) << m[2];
  EXPECT_NE(m[2].find("'knee'"), std::string::npos) << m[2];
  EXPECT_EQ(m[3].rfind("7:22 error: ", 0), 0u) << m[3];
  EXPECT_NE(m[3].find("did you mean 'wrist_pitch'"), std::string::npos) << m[3];
  EXPECT_EQ(m[4], "7:40 error: a joint's 'sign' must be 1 or -1");
}

TEST(ArmGeometry, AProfileWithoutGeometryNeedsItAll) {
  const auto out = compile_text(R"(robot:
  profile: lsc-6
  arm:
    upper_arm: 100
    joints:
      base: {servo: ch6}
sequence:
  - move: {ch1: 1600}
    time: 1s
)");
  const std::vector<std::string> m = messages(out);
  ASSERT_EQ(m.size(), 1u) << diagnostics_of(out);
  EXPECT_EQ(m[0],
            "4:5 error: 'arm' on lsc-6 (no built-in geometry) needs base_height, forearm, hand, "
            "joints: shoulder: servo, joints: elbow: servo, joints: wrist: servo");
  // Given everything, the PWM board's degrees (2000 us over 180 deg) scale its angles.
  const auto full = compile_text(R"(robot:
  profile: lsc-6
  arm:
    base_height: 60
    upper_arm: 100
    forearm: 90
    hand: 110
    joints:
      base: {servo: ch6}
      shoulder: {servo: ch5}
      elbow: {servo: ch4}
      wrist: {servo: ch3}
sequence:
  - move: {ch1: 1600}
    time: 1s
)");
  const compiler::ServoProgram& p = program_of(full);
  ASSERT_TRUE(p.robot.arm.has_value());
  EXPECT_EQ(p.robot.arm->shoulder, (compiler::ArmJoint{"ch5", 1500, 1}));
  // Shoulder 90 deg is 1000 us past its zero (1500).
  expect_tip(tip(*p.robot.arm, {{"ch6", 1500}, {"ch5", 2500}, {"ch4", 1500}, {"ch3", 1500}}),
             100 + 90 + 110, 0, 60);
}

TEST(ArmGeometry, BoardsWithoutAnArmHaveNone) {
  EXPECT_FALSE(program_of(compile_text("robot: lsc-16\nsequence:\n  - move: {ch1: 1600}\n"
                                       "    time: 1s\n"))
                   .robot.arm.has_value());
  const auto car = compile_text("robot:\n  profile: raspblock\n  arm: {hand: 3}\nsequence: []\n");
  const std::vector<std::string> m = messages(car);
  ASSERT_FALSE(m.empty());
  EXPECT_EQ(m[0], "3:8 error: 'arm' is for servo controllers; raspblock has no arm");
}

TEST(ArmGeometry, SimulateAddsTheTipInMillimetres) {
  const auto out = compile_text(R"(robot: xarm
sequence:
  - move: {shoulder: 125}
    time: 1s
)");
  // Half way the shoulder is at 312.5, 45 deg: r = 343 sin 45, z = 72 + 343 cos 45.
  const double half = 343 * std::sin(45 * kDeg);
  char mid[64];
  std::snprintf(mid, sizeof mid, "500,313,%.2f,0.00,%.2f\n", half, 72 + half);
  EXPECT_EQ(to_csv(simulate(program_of(out), 500)),
            std::string("time_ms,shoulder,tip_x,tip_y,tip_z\n"
                        "0,500,0.00,0.00,415.00\n") +
                mid + "1000,125,343.00,0.00,72.00\n");
  EXPECT_EQ(std::string(mid), "500,313,242.54,0.00,314.54\n");
  // No geometry, no tip columns.
  const auto pwm = compile_text("robot: lsc-16\nsequence:\n  - move: {ch1: 1600}\n    time: 1s\n");
  EXPECT_EQ(to_csv(simulate(program_of(pwm), 1000)), "time_ms,ch1\n0,1500\n1000,1600\n");
}

}  // namespace
}  // namespace seqc::compiler
