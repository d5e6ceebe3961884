#include "compiler/program/arm_kinematics.hpp"

#include <cmath>
#include <numbers>

namespace seqc::compiler {

ArmPoints arm_points(const compiler::ArmGeometry& arm,
                     const std::function<double(std::string_view)>& position) {
  return arm_points(arm,
                    std::array<double, 4>{position(arm.base.servo), position(arm.shoulder.servo),
                                          position(arm.elbow.servo), position(arm.wrist.servo)});
}

ArmPoints arm_points(const compiler::ArmGeometry& arm, const std::array<double, 4>& joints) {
  auto radians = [&](const compiler::ArmJoint& j, double position) {
    return j.sign * (position - j.zero) * arm.degrees_per_unit * std::numbers::pi / 180;
  };
  const double base = radians(arm.base, joints[0]);
  const double s = radians(arm.shoulder, joints[1]);
  const double se = s + radians(arm.elbow, joints[2]);
  const double sew = se + radians(arm.wrist, joints[3]);
  ArmPoints out;
  out.base_degrees = base * 180 / std::numbers::pi;
  // Each point in the arm's plane (r out from the base axis, z up), then turned with the base.
  const double cb = std::cos(base), sb = std::sin(base);
  auto place = [cb, sb](double r, double z) { return std::array<double, 3>{r * cb, r * sb, z}; };
  double r = 0, z = arm.base_height;
  out.shoulder = place(r, z);
  r += arm.upper_arm * std::sin(s), z += arm.upper_arm * std::cos(s);
  out.elbow = place(r, z);
  r += arm.forearm * std::sin(se), z += arm.forearm * std::cos(se);
  out.wrist = place(r, z);
  r += arm.hand * std::sin(sew), z += arm.hand * std::cos(sew);
  out.tip = place(r, z);
  return out;
}

double tip_height(const compiler::ArmGeometry& arm, const std::array<double, 4>& joints) {
  auto radians = [&](const compiler::ArmJoint& j, double position) {
    return j.sign * (position - j.zero) * arm.degrees_per_unit * std::numbers::pi / 180;
  };
  const double s = radians(arm.shoulder, joints[1]);
  const double se = s + radians(arm.elbow, joints[2]);
  const double sew = se + radians(arm.wrist, joints[3]);
  return arm.base_height + arm.upper_arm * std::cos(s) + arm.forearm * std::cos(se) +
         arm.hand * std::cos(sew);
}

}  // namespace seqc::compiler
