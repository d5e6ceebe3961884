// Inverse kinematics of an arm (compiler/program/arm_geometry.hpp): the joint angles that put the
// claw's tip at a point with the hand at a pitch, in the conventions of the forward kinematics
// (program/arm_kinematics.hpp), which this inverts exactly for a reachable point. Angles are in
// degrees; turning them into servo positions (zero, sign, units) is the caller's.
#pragma once

#include <array>
#include <optional>

#include "compiler/program/arm_geometry.hpp"

namespace seqc::compiler {

struct ArmAngles {
  double base = 0, shoulder = 0, elbow = 0, wrist = 0;  // degrees
};

struct ArmSolution {
  std::optional<ArmAngles> angles;  // nullopt: out of reach
  // Out of reach: the shoulder-to-wrist distance the point needs and the nearest the upper arm
  // and forearm can span (their sum when too far, their difference when too near).
  double needed = 0, reach = 0;
};

// The tip at `tip` (x, y, z in mm) with the hand's pitch `pitch_degrees` (0 up, 90 level, 180
// down). `elbow_up`: the elbow above the line from the shoulder to the wrist (the other of the
// two solutions otherwise). `base_degrees` is kept when the point is on the base's axis, where
// any base angle serves.
ArmSolution solve_arm(const compiler::ArmGeometry& arm, const std::array<double, 3>& tip,
                      double pitch_degrees, bool elbow_up, double base_degrees);

}  // namespace seqc::compiler
