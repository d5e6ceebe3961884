// Poses as text a person pastes or seqc appends into a choreography: the pose line
// ("  ready: {claw: 300, elbow: 650}"), and the edit that adds one to a file's `poses:` section
// while leaving every other byte of the file as it was (comments, order, layout), the way a
// person would edit it, instead of re-serialising the YAML.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "base/result.hpp"
#include "compiler/program/program.hpp"

namespace seqc::compiler {

// "NAME: {servo: position, ...}" with the robot's servo names, in the order given.
std::string pose_line(const std::string& name,
                      const std::vector<std::pair<std::uint8_t, std::uint16_t>>& positions,
                      const compiler::RobotInfo& robot);

// `text` with "  NAME: {...}" (the section's own indentation) added as the last entry of its
// top-level `poses:` block; without one, a `poses:` block is added before `sequence:` (or at
// the end). Errors: `poses:` written inline (`poses: {...}`), or NAME already a pose there.
Result<std::string> add_pose(const std::string& text, const std::string& pose_line_text,
                             const std::string& name);

// The names of the poses in the file's top-level `poses:` block, as written.
std::vector<std::string> pose_names(const std::string& text);

// The first of pose1, pose2, ... that is not yet a pose of the file (a name to offer).
std::string next_pose_name(const std::string& text);

// Whether `name` can name a pose: letters, digits and _, not starting with a digit (the
// language's names).
bool is_pose_name(const std::string& name);

}  // namespace seqc::compiler
