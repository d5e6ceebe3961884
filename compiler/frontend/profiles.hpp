// Built-in robot profiles: what `robot: xarm` (or bus, lsc-16, lsc-32, lsc-6, learm, raspblock)
// means before the file's own servo definitions are applied.
//
// This table is where a new robot kind plugs in: add a RobotKind (program/program.hpp), a profile
// row here, and the lowering for that kind (compile.cpp dispatches on the profile's kind). A new
// board for an existing kind needs only a row naming its board.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "compiler/program/controller_model.hpp"
#include "compiler/program/program.hpp"
#include "protocol/lsc/group_download.hpp"

namespace seqc::compiler {

struct RobotProfile {
  std::string_view name;
  RobotKind kind = RobotKind::ServoController;
  // The board that runs its programs: a key of the runtime's table of boards
  // (runtime/boards/board.hpp), copied into RobotInfo::board.
  std::string_view board;
  std::uint8_t first_id = 0;  // ids (bus ids or PWM channels) the controller accepts
  std::uint8_t last_id = 0;
  int min = 0;  // position range in device units
  int max = 0;
  int home = 0;
  // Degrees: units = degree_zero + degrees * units_per_degree (0deg is the low end of travel).
  double degree_zero = 0;
  double units_per_degree = 1;
  // Names of the profile's servos; ids without a name here are called <default_prefix><id>.
  std::vector<std::pair<std::string_view, std::uint8_t>> names;
  std::string_view default_prefix;
  // The stock servo's rated speed, device units per second: every servo's default max_speed
  // (0: none).
  double rated_speed = 0;
  // Actions one stored group holds on this controller.
  std::size_t max_actions = lsc::kMaxActions;
  // The arm's built-in geometry (its degrees_per_unit is taken from units_per_degree), if any.
  const ArmGeometry* arm = nullptr;
  // How the controller moves a servo during an action (compiler/program/controller_model.hpp);
  // fitting keeps every tolerance under this model. docs/language.md says why each profile has its
  // own.
  ControllerModel controller = ControllerModel::StraightLine;
};

const RobotProfile* find_profile(std::string_view name);

// What a position of the profile's servos counts, as plots and the preview label it: "us" (the
// pulse width in microseconds) for the PWM boards, lsc-16, lsc-32, lsc-6 and learm; "units" for
// the bus servos' 0-1000.
std::string_view position_unit(std::string_view profile);
std::vector<std::string> profile_names();
// "xarm, lsc-16, lsc-32" style list for messages, so adding a profile updates them all.
std::string profile_list();

// The RobotInfo a profile describes before any per-file servo definitions.
RobotInfo robot_from_profile(const RobotProfile& profile);

// The number of actions a group holds for `profile` (lsc::kMaxActions for an unknown name), and
// the end of the message for a sequence that needs one more: "a group holds at most 1,020 (4
// blocks of 255), and this step makes action 1,021".
std::size_t group_capacity(const RobotProfile* profile);
// How many groups the profile's board stores, numbered from 0: the xArm family's group byte
// runs 0-254 (255 names every group), the LSC-6's 0-255.
std::size_t stored_groups(const RobotProfile* profile);
std::string group_capacity_text(const RobotProfile* profile);

}  // namespace seqc::compiler
