// Forward kinematics of an arm (compiler/program/arm_geometry.hpp): where the claw's tip is for
// given joint positions. The conventions, which the preview page's script mirrors and `seqc
// simulate`'s tip columns print:
//   - a joint angle is sign * (position - zero) * degrees_per_unit;
//   - with every angle 0 the arm points straight up;
//   - the base turns about the vertical axis: 0 faces +x, positive is counter-clockwise seen
//     from above;
//   - shoulder, elbow and wrist tilt in the arm's vertical plane, positive away from the base
//     axis, each angle adding to the one before.
// With U, F, H the upper arm, forearm and hand and s, e, w their angles:
//   r = U sin s + F sin(s+e) + H sin(s+e+w), z = base_height + U cos s + F cos(s+e) + H cos(s+e+w),
//   x = r cos(base), y = r sin(base).
#pragma once

#include <array>
#include <functional>
#include <string_view>

#include "compiler/program/arm_geometry.hpp"

namespace seqc::compiler {

struct ArmPoints {
  // x, y, z in mm of the shoulder axis, the elbow, the wrist and the tip.
  std::array<double, 3> shoulder{}, elbow{}, wrist{}, tip{};
  double base_degrees = 0;  // the base's angle (the arm's vertical plane)
};

// `position` gives a servo's position (device units) by name.
ArmPoints arm_points(const compiler::ArmGeometry& arm,
                     const std::function<double(std::string_view)>& position);

// The same points from the positions of the base, shoulder, elbow and wrist servos in that
// order: the form for callers that evaluate the tip at every millisecond of a move.
ArmPoints arm_points(const compiler::ArmGeometry& arm, const std::array<double, 4>& joints);

// Only the tip's height above the table (mm), as arm_points(arm, joints).tip[2] gives it: the
// form for checks that sample a move at every millisecond and need nothing else.
double tip_height(const compiler::ArmGeometry& arm, const std::array<double, 4>& joints);

}  // namespace seqc::compiler
