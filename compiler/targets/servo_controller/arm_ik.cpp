#include "compiler/targets/servo_controller/arm_ik.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace seqc::compiler {

ArmSolution solve_arm(const compiler::ArmGeometry& arm, const std::array<double, 3>& tip,
                      double pitch_degrees, bool elbow_up, double base_degrees) {
  constexpr double kDeg = 180 / std::numbers::pi;
  const double radius = std::hypot(tip[0], tip[1]);
  // On the axis (within a micrometre) the base angle is free: keep it rather than spin.
  const double base = radius < 1e-3 ? base_degrees : std::atan2(tip[1], tip[0]) * kDeg;
  // The wrist is the hand's length back from the tip along the pitch; the rest is the two-link
  // problem of the upper arm and forearm in the arm's plane, angles measured from the vertical.
  const double pitch = pitch_degrees / kDeg;
  const double r = radius - arm.hand * std::sin(pitch);
  const double z = tip[2] - arm.base_height - arm.hand * std::cos(pitch);
  const double u = arm.upper_arm, f = arm.forearm;
  const double d = std::hypot(r, z);
  ArmSolution out;
  out.needed = d;
  if (d > u + f) {
    out.reach = u + f;
    return out;
  }
  if (d < std::abs(u - f)) {
    out.reach = std::abs(u - f);
    return out;
  }
  // Law of cosines for the elbow; clamped because d on the boundary may round just outside.
  const double c = std::clamp((d * d - u * u - f * f) / (2 * u * f), -1.0, 1.0);
  // Positive elbow bends the forearm further from the axis than the upper arm, which leaves the
  // elbow above the shoulder-to-wrist line.
  const double e = (elbow_up ? 1 : -1) * std::acos(c);
  const double s = std::atan2(r, z) - std::atan2(f * std::sin(e), u + f * std::cos(e));
  out.angles = ArmAngles{base, s * kDeg, e * kDeg, pitch_degrees - (s + e) * kDeg};
  return out;
}

}  // namespace seqc::compiler
