// The programs the compiler produces: target-neutral data that the targets' back ends, the
// formats (listing, simulate, plot, preview, .d6a) and the runtime read. One alternative per
// robot kind in the Program variant: the servo controller (xArm / LSC boards) with its stored
// action groups, and the Raspblock car with its timed packet stream. A program also carries what
// the author meant (the timeline) and the robot it was compiled for (RobotInfo), including the
// board that runs it (RobotInfo::board), which the runtime looks up in its table of boards; the
// compiler itself never chooses between boards. Nothing here depends on the front end.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "base/source.hpp"
#include "compiler/program/arm_geometry.hpp"
#include "compiler/program/controller_model.hpp"
#include "compiler/program/raspblock_program.hpp"
#include "compiler/timeline/timeline.hpp"
#include "protocol/lsc/lsc_messages.hpp"

namespace seqc::compiler {

enum class RobotKind {
  ServoController,  // xArm / LSC-16 / LSC-32 / LSC-6: keyframes stored as an action group
  Raspblock,        // Yahboom Raspblock car board: a timed packet stream, played live
};

// One servo as the program sees it, after the file's `robot:` section is applied.
struct ServoInfo {
  std::string name;     // the name diagnostics and listings use
  std::uint8_t id = 0;  // bus id (xArm) or PWM channel (LSC)
  int min = 0;          // limits in device units
  int max = 0;
  int home = 0;                     // centre for mirroring; simulator's starting position
  std::optional<double> max_speed;  // device units per second; nullopt = unchecked
  std::optional<double> max_accel;  // device units per second squared; nullopt = unchecked
};

struct RobotInfo {
  std::string profile;  // "xarm", "bus", "lsc-16", "lsc-32", "lsc-6", "learm", "raspblock"
  std::string board;    // the board that runs it (RobotProfile::board): "xarm", "lsc6", ...
  RobotKind kind = RobotKind::ServoController;
  std::vector<ServoInfo> servos;  // in id order
  // The highest id the file's `servos:` section names (0 when it names none).
  std::uint8_t highest_defined_id = 0;
  // Link lengths and joint servos, for an arm whose profile or file gives them.
  std::optional<ArmGeometry> arm;

  const ServoInfo* find_id(std::uint8_t id) const;
  const ServoInfo* find_name(std::string_view name) const;
};

// Where the robot stands when it runs, for a servo whose first move is relative to it
// (`move: {base: +100}` before any absolute move of 'base'). Only the xArm family's bus servos
// can say where they stand (servos_report_positions), and only once the robot is there.
struct RobotStart {
  // Read from the servos just before the run (`upload --run`, `play`): id -> position. Such a
  // move then starts from its servo's reading, as a move from a known position.
  std::map<std::uint8_t, std::uint16_t> read{};
  // Without a reading: true checks the move from the servo's home and says so in a note
  // (`check`); false makes it an error naming what reads the servos (`compile`, `upload`).
  bool assume_home = false;
};

// Whether `robot`'s servos report where they stand (ServoPositionRead): bus servos, whose range
// starts at 0; a PWM servo's (500..2500 us) does not, and it has no position to report.
bool servos_report_positions(const RobotInfo& robot);

// One controller action: move the listed servos to their positions over time_ms. Servos not
// listed keep their position. A wait is an action that re-sends the held positions.
struct Keyframe {
  std::uint32_t start_ms = 0;             // when the action starts, from the start of the sequence
  std::uint16_t time_ms = 0;              // kMinActionMs..kMaxActionMs
  std::vector<lsc::ServoTarget> targets;  // ascending id, each id once
  Location source;                        // the step it came from
};

struct ServoProgram {
  RobotInfo robot;
  std::vector<Keyframe> keyframes;
  // How many actions one stored group holds on the profile's board: the budget the lowering
  // kept keyframes within, set once there so that no reader works it out again.
  std::size_t group_capacity = 0;
  // Groups it was allowed to take, one after another (CompileOptions::chain): keyframes may number
  // up to group_capacity x groups, and compiler/targets/servo_controller/chain.hpp cuts them.
  std::size_t groups = 1;
  // A dance longer than one group (chain.hpp): the bar (from 1; 0 without bar lines) each of
  // its groups starts on, in order; empty when one group holds it.
  std::vector<std::int64_t> group_bars;
  // The ids of the servos whose first move is relative to where the robot stands (RobotStart):
  // a run reads them and compiles again from the readings.
  std::vector<std::uint8_t> start_reads;
  // What the author meant, per servo (by index into robot.servos), before fitting.
  Timeline timeline;
  // The largest distance between the compiled motion and the intended curve, and where.
  double fit_error = 0;
  std::uint32_t fit_error_at_ms = 0;
  std::string fit_error_servo;
  // With `path: line` moves: the largest distance (mm) between the claw's tip, by forward
  // kinematics of the joints as the controller moves them, and the line's point, over every
  // millisecond of every line, and where; nullopt without a line. The joints' own pieces of a
  // line are straight between whole units, so fit_error says nothing of them.
  std::optional<double> tip_error_mm;
  std::uint32_t tip_error_at_ms = 0;
  // How the profile's controller moves a servo during an action: what fitting kept every
  // tolerance under, and what `seqc simulate --compare` measures.
  ControllerModel controller = ControllerModel::StraightLine;
  std::uint64_t duration_ms() const;
};

// One alternative per RobotKind.
using Program = std::variant<ServoProgram, RaspblockProgram>;

}  // namespace seqc::compiler
