// `seqc servo read|off|move|mode`: single servos on the servo controller (ServoPositionRead,
// MultiServoOff, MultiServoMove, ServoSpeed). With --robot PROFILE, servos may be named
// (claw=200) and positions are checked against the profile's range; without one against every
// servo controller's (boards::position_range). A position outside it sends nothing (exit 1).
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "base/units.hpp"
#include "compiler/formats/pose_text.hpp"
#include "runtime/boards/board.hpp"
#include "runtime/boards/servo_args.hpp"
#include "runtime/boards/xarm_queries.hpp"
#include "runtime/cli/board_text.hpp"
#include "runtime/cli/commands.hpp"
#include "runtime/cli/device_args.hpp"
#include "runtime/cli/device_command.hpp"

namespace seqc::cli {
namespace {

// ---- read ----------------------------------------------------------------------------------

struct ReadOptions : ServoListOptions {
  std::string format = "table";
  std::string name = "pose1";
};

ExitCode read_positions(Context& ctx, const ReadOptions& o) {
  // A pose needs servo names: yaml uses the board's pose profile when no --robot is given.
  const boards::Board& board = boards::board_for_command(o.device.profile(), o.device.port);
  const bool named = o.robot.empty() && o.format == "yaml";
  auto robot = boards::robot_for_profile(named ? std::string(board.pose_profile) : o.robot);
  if (!robot) return usage_error(ctx, robot.error().message);
  auto ids = boards::servos_to_read(o.servos, *robot);
  if (!ids) return usage_error(ctx, ids.error().message);
  return run_on_controller(ctx, o.device, [&](boards::XarmSession& s) {
    auto answered = boards::read_positions(s, *ids);
    if (!answered) return ExitCode::DeviceFailure;
    if (o.format == "yaml") {
      // A line to paste under `poses:` (seqc teach adds them to a file itself).
      std::vector<std::pair<std::uint8_t, std::uint16_t>> positions;
      for (const lsc::ServoTarget& t : *answered) positions.emplace_back(t.id, t.position);
      ctx.out << "  " << compiler::pose_line(o.name, positions, **robot) << "\n";
      if (positions.size() != ids->size()) {
        return fail(ctx, ExitCode::DeviceFailure,
                    std::to_string(ids->size() - positions.size()) +
                        " servo(s) did not answer; the pose lacks them");
      }
      return ExitCode::Ok;
    }
    return print_servo_readings(
        ctx,
        boards::servo_readings(*ids, *robot, "position", *answered, &lsc::ServoTarget::position),
        *robot);
  });
}

// ---- off -----------------------------------------------------------------------------------

ExitCode servos_off(Context& ctx, const ServoListOptions& o) {
  auto sel = boards::select_servos(o.robot, o.servos);
  if (!sel) return usage_error(ctx, sel.error().message);
  return tell_on_controller(ctx, o.device, lsc::MultiServoOff{sel->ids},
                            servo_labels(sel->ids, sel->robot) + ": off (no torque)\n");
}

// ---- move ----------------------------------------------------------------------------------

struct MoveOptions {
  DeviceOptions device;
  std::vector<std::string> targets;
  std::string time = "1s";
  std::string robot;
};

ExitCode move_servos(Context& ctx, const MoveOptions& o) {
  auto robot = boards::robot_for_profile(o.robot);
  if (!robot) return usage_error(ctx, robot.error().message);
  auto ms = boards::parse_milliseconds(o.time, "--time");
  if (!ms) return usage_error(ctx, ms.error().message);
  auto requested = boards::parse_targets(o.targets, *robot);
  if (!requested) return usage_error(ctx, requested.error().message);
  // A position no servo there can reach is a bad value, not a bad command line.
  auto targets = boards::checked_targets(*requested, *robot);
  if (!targets) {
    return fail(ctx, ExitCode::InvalidInput, targets.error().message + "; nothing was sent");
  }
  std::string summary;
  for (const lsc::ServoTarget& t : *targets) {
    summary += (summary.empty() ? "" : ", ") + servo_label(t.id, *robot) + " to " +
               std::to_string(t.position);
  }
  const std::string said = "moving " + summary + " over " + seqc::format_seconds(*ms);
  const boards::Board& board = boards::board_for_command(o.device.profile(), o.device.port);
  if (board.move == nullptr) return refuse_command(ctx, board, o.device.command);
  return run_on_board(ctx, o.device, board, [&](const boards::Line& line, const std::string& port) {
    const boards::Outcome r = board.move(line, *targets, *ms);
    if (!r.ok()) return report_outcome(ctx, r, line, port, board);
    summarize(ctx, board.confirms_moves
                       ? said
                       : said + " (the " + std::string(board.name) + " does not confirm moves)");
    return ExitCode::Ok;
  });
}

// ---- mode ----------------------------------------------------------------------------------

struct ModeOptions {
  DeviceOptions device;
  std::string servo;
  std::string mode;
  std::string time;
  std::string robot;
};

ExitCode set_mode(Context& ctx, const ModeOptions& o) {
  auto robot = boards::robot_for_profile(o.robot);
  if (!robot) return usage_error(ctx, robot.error().message);
  auto id = boards::parse_servo(o.servo, *robot);
  if (!id) return usage_error(ctx, id.error().message);
  auto ms = boards::parse_milliseconds(o.time, "--time");
  if (!ms) return usage_error(ctx, ms.error().message);
  const lsc::ServoMode mode = o.mode == "motor" ? lsc::ServoMode::Motor : lsc::ServoMode::Servo;
  return tell_on_controller(
      ctx, o.device, lsc::ServoSpeed{*id, mode, *ms},
      servo_label(*id, *robot) + ": " + o.mode + " mode, " + std::to_string(*ms) + " ms\n");
}

}  // namespace

void add_servo_command(CLI::App& app, Context& ctx, Outcome& result) {
  CLI::App* servo =
      app.add_subcommand("servo", "Read, move or release single servos on the servo controller");
  servo->require_subcommand(1);

  auto read = std::make_shared<ReadOptions>();
  CLI::App* read_cmd =
      servo->add_subcommand("read", "Print the positions of servos as a table (ServoPositionRead)");
  read_cmd->add_option("SERVO", read->servos,
                       "Servo ids (or names with --robot); default with --robot: all of them");
  add_robot_option(*read_cmd, read->robot);
  read_cmd
      ->add_option("--format", read->format,
                   "table (default), or yaml: a pose line to paste under poses: (servo names "
                   "from --robot, else the xArm's)")
      ->check(CLI::IsMember({"table", "yaml"}));
  read_cmd->add_option("--name", read->name, "With --format yaml: the pose's name (default pose1)");
  add_device_options(*read_cmd, read->device);
  read_cmd->callback([read, &ctx, &result] { result.code = read_positions(ctx, *read); });

  auto off = std::make_shared<ServoListOptions>();
  CLI::App* off_cmd = servo->add_subcommand(
      "off", "Turn servos off: they stop where they are and go limp (MultiServoOff)");
  add_servo_list_options(*off_cmd, *off);
  off_cmd->callback([off, &ctx, &result] { result.code = servos_off(ctx, *off); });

  auto move = std::make_shared<MoveOptions>();
  CLI::App* move_cmd = servo->add_subcommand(
      "move", "Move servos to positions together, e.g. `1=500 2=700 --time 1s` (MultiServoMove)");
  move_cmd
      ->add_option("TARGET", move->targets, "SERVO=POSITION, e.g. 1=500 (claw=200 with --robot)")
      ->required();
  move_cmd->add_option("--time", move->time, "How long the move takes (ms or s, at most 65535ms)")
      ->capture_default_str();
  add_robot_option(*move_cmd, move->robot);
  add_device_options(*move_cmd, move->device);
  move_cmd->callback([move, &ctx, &result] { result.code = move_servos(ctx, *move); });

  auto mode = std::make_shared<ModeOptions>();
  CLI::App* mode_cmd = servo->add_subcommand(
      "mode",
      "Switch a servo between servo (position) and motor (continuous turn) mode, with the\n"
      "document's milliseconds field (ServoSpeed)");
  mode_cmd->add_option("SERVO", mode->servo, "Servo id (or name with --robot)")->required();
  mode_cmd->add_option("MODE", mode->mode, "servo or motor")
      ->required()
      ->check(CLI::IsMember({"servo", "motor"}));
  mode_cmd->add_option("--time", mode->time, "The milliseconds field (ms or s, at most 65535ms)")
      ->required();
  add_robot_option(*mode_cmd, mode->robot);
  add_device_options(*mode_cmd, mode->device);
  mode_cmd->callback([mode, &ctx, &result] { result.code = set_mode(ctx, *mode); });
}

}  // namespace seqc::cli
