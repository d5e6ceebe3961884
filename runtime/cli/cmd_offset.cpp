// `seqc offset read|adjust|write`: servo position offsets (ServoOffsetRead, ServoOffsetAdjust,
// ServoOffsetWrite). Adjusting is volatile; writing keeps the current offset over power-off
// (the bus-servo convention; docs/protocol/servo-controller.md, "Offsets").
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "runtime/boards/servo_args.hpp"
#include "runtime/cli/commands.hpp"
#include "runtime/cli/device_args.hpp"
#include "runtime/cli/device_command.hpp"

namespace seqc::cli {
namespace {

struct AdjustOptions {
  DeviceOptions device;
  std::string servo;
  std::string offset;
  std::string robot;
};

ExitCode read_offsets(Context& ctx, const ServoListOptions& o) {
  auto sel = boards::select_servos(o.robot, o.servos);
  if (!sel) return usage_error(ctx, sel.error().message);
  return run_on_controller(ctx, o.device, [&](boards::XarmSession& s) {
    auto reply = s.ask<lsc::ServoOffsets>(lsc::ServoOffsetRead{sel->ids}, "the offsets");
    if (!reply) return ExitCode::DeviceFailure;
    return print_servo_readings(
        ctx,
        boards::servo_readings(sel->ids, sel->robot, "offset", reply->servos,
                               &lsc::ServoOffsets::Entry::offset),
        sel->robot);
  });
}

ExitCode adjust_offset(Context& ctx, const AdjustOptions& o) {
  auto robot = boards::robot_for_profile(o.robot);
  if (!robot) return usage_error(ctx, robot.error().message);
  auto id = boards::parse_servo(o.servo, *robot);
  if (!id) return usage_error(ctx, id.error().message);
  auto offset = boards::parse_offset(o.offset);
  if (!offset) return usage_error(ctx, offset.error().message);
  return tell_on_controller(
      ctx, o.device, lsc::ServoOffsetAdjust{*id, *offset},
      servo_label(*id, *robot) + ": offset set to " + std::to_string(*offset) +
          " (volatile: lost at power-off unless written with `seqc offset write " +
          std::to_string(int{*id}) + "`)\n");
}

ExitCode write_offsets(Context& ctx, const ServoListOptions& o) {
  auto sel = boards::select_servos(o.robot, o.servos);
  if (!sel) return usage_error(ctx, sel.error().message);
  return tell_on_controller(
      ctx, o.device, lsc::ServoOffsetWrite{sel->ids},
      servo_labels(sel->ids, sel->robot) + ": offset written (kept over power-off)\n");
}

}  // namespace

void add_offset_command(CLI::App& app, Context& ctx, Outcome& result) {
  CLI::App* offset = app.add_subcommand(
      "offset", "Read, adjust (volatile) or write (kept over power-off) servo offsets");
  offset->require_subcommand(1);

  auto read = std::make_shared<ServoListOptions>();
  CLI::App* read_cmd =
      offset->add_subcommand("read", "Print servo offsets as a table (ServoOffsetRead)");
  add_servo_list_options(*read_cmd, *read);
  read_cmd->callback([read, &ctx, &result] { result.code = read_offsets(ctx, *read); });

  auto adjust = std::make_shared<AdjustOptions>();
  CLI::App* adjust_cmd = offset->add_subcommand(
      "adjust",
      "Set a servo's offset (ServoOffsetAdjust). Volatile: lost at power-off unless written\n"
      "with `seqc offset write`");
  adjust_cmd->add_option("SERVO", adjust->servo, "Servo id (or name with --robot)")->required();
  adjust_cmd->add_option("OFFSET", adjust->offset, "Offset in position units, -128..127")
      ->required();
  add_robot_option(*adjust_cmd, adjust->robot);
  add_device_options(*adjust_cmd, adjust->device);
  adjust_cmd->callback([adjust, &ctx, &result] { result.code = adjust_offset(ctx, *adjust); });

  auto write = std::make_shared<ServoListOptions>();
  CLI::App* write_cmd = offset->add_subcommand(
      "write", "Keep servos' current offsets over power-off (ServoOffsetWrite)");
  add_servo_list_options(*write_cmd, *write);
  write_cmd->callback([write, &ctx, &result] { result.code = write_offsets(ctx, *write); });
}

}  // namespace seqc::cli
