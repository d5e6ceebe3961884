// An arm's geometry as the program carries it (RobotInfo::arm): link lengths in millimetres and
// which servo drives each joint, with the position where that joint's angle is 0 and the
// direction it turns. The profile table gives a built-in one (frontend/profiles.cpp) and a file's
// `robot: {arm: ...}` may override any of it (frontend/robot_section.cpp); the forward kinematics
// over it are program/arm_kinematics.hpp.
#pragma once

#include <string>

namespace seqc::compiler {

struct ArmJoint {
  std::string servo;  // a servo name of the robot
  double zero = 500;  // the position (device units) at which the joint's angle is 0
  int sign = 1;       // +1 or -1: whether a larger position turns the joint the positive way
  friend bool operator==(const ArmJoint&, const ArmJoint&) = default;
};

struct ArmGeometry {
  double base_height = 0;  // mm from the table to the shoulder axis
  double upper_arm = 0;    // mm, shoulder axis to elbow axis
  double forearm = 0;      // mm, elbow axis to wrist axis
  double hand = 0;         // mm, wrist axis to the tip of the claw
  ArmJoint base, shoulder, elbow, wrist;
  double degrees_per_unit = 1;  // the profile's: a joint angle is sign * (position - zero) * this
  std::string claw;             // the servo that opens the claw ("" when none)
  friend bool operator==(const ArmGeometry&, const ArmGeometry&) = default;
};

}  // namespace seqc::compiler
