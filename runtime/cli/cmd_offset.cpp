// `seqc offset read|adjust|write`: servo position offsets (ServoOffsetRead, ServoOffsetAdjust,
// ServoOffsetWrite). Adjusting is volatile; writing keeps the current offset over power-off
// (the bus-servo convention; protocol-notes.md A, "Offsets").
#include <algorithm>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "runtime/cli/commands.hpp"
#include "runtime/cli/controller_session.hpp"
#include "runtime/cli/device_args.hpp"
#include "runtime/cli/device_table.hpp"

namespace seqc::cli {
namespace {

// Reading of the document: ServoOffsetAdjust sends a (short) but ServoOffsetRead reports a
// (sbyte), so only -128..127 can be set and read back; larger values are refused here rather
// than sent and silently ignored or misreported.
constexpr long long kOffsetMin = -128;
constexpr long long kOffsetMax = 127;

struct Options {
  DeviceOptions device;
  std::vector<std::string> servos;
  std::string servo;
  std::string offset;
  std::string robot;
};

ExitCode read_offsets(Context& ctx, const Options& o) {
  auto robot = robot_for_profile(o.robot);
  if (!robot) return usage_error(ctx, robot.error().message);
  auto ids = parse_servo_list(o.servos, *robot);
  if (!ids) return usage_error(ctx, ids.error().message);
  return run_on_controller(ctx, o.device, [&](ControllerSession& s) {
    auto reply = s.ask<lsc::ServoOffsets>(lsc::ServoOffsetRead{*ids}, "the offsets");
    if (!reply) return ExitCode::DeviceFailure;
    Table table(*robot ? std::vector<std::string>{"servo", "name", "offset"}
                       : std::vector<std::string>{"servo", "offset"});
    std::vector<std::uint8_t> missing;
    for (std::uint8_t id : *ids) {
      auto it = std::find_if(reply->servos.begin(), reply->servos.end(),
                             [id](const lsc::ServoOffsets::Entry& e) { return e.id == id; });
      std::vector<std::string> row{std::to_string(id)};
      if (*robot) row.push_back((*robot)->find_id(id)->name);
      if (it == reply->servos.end()) {
        missing.push_back(id);
        row.push_back("no answer");
      } else {
        row.push_back(std::to_string(it->offset));
      }
      table.add(std::move(row));
    }
    ctx.out << table.render();
    if (!missing.empty()) {
      ctx.err << "seqc: error: the controller reported no offset for "
              << servo_labels(missing, *robot) << " (not on the bus, or not answering)\n";
      return ExitCode::DeviceFailure;
    }
    return ExitCode::Ok;
  });
}

ExitCode adjust_offset(Context& ctx, const Options& o) {
  auto robot = robot_for_profile(o.robot);
  if (!robot) return usage_error(ctx, robot.error().message);
  auto id = parse_servo(o.servo, *robot);
  if (!id) return usage_error(ctx, id.error().message);
  auto number = parse_integer(o.offset, "offset");
  if (!number) return usage_error(ctx, number.error().message);
  auto offset = lsc::checked_i16(*number, "offset");
  if (!offset) return usage_error(ctx, offset.error().message);
  if (*number < kOffsetMin || *number > kOffsetMax) {
    return usage_error(ctx, "offset must be " + std::to_string(kOffsetMin) + ".." +
                                std::to_string(kOffsetMax) + ", got " + std::to_string(*number) +
                                " (ServoOffsetRead reports offsets as a signed byte)");
  }
  return run_on_controller(ctx, o.device, [&](ControllerSession& s) {
    if (!s.tell(lsc::ServoOffsetAdjust{*id, *offset})) return ExitCode::DeviceFailure;
    ctx.out << servo_label(*id, *robot) << ": offset set to " << *offset
            << " (volatile: lost at power-off unless written with `seqc offset write " << int{*id}
            << "`)\n";
    return ExitCode::Ok;
  });
}

ExitCode write_offsets(Context& ctx, const Options& o) {
  auto robot = robot_for_profile(o.robot);
  if (!robot) return usage_error(ctx, robot.error().message);
  auto ids = parse_servo_list(o.servos, *robot);
  if (!ids) return usage_error(ctx, ids.error().message);
  return run_on_controller(ctx, o.device, [&](ControllerSession& s) {
    if (!s.tell(lsc::ServoOffsetWrite{*ids})) return ExitCode::DeviceFailure;
    ctx.out << servo_labels(*ids, *robot) << ": offset written (kept over power-off)\n";
    return ExitCode::Ok;
  });
}

}  // namespace

void add_offset_command(CLI::App& app, Context& ctx, Outcome& result) {
  CLI::App* offset = app.add_subcommand(
      "offset", "Read, adjust (volatile) or write (kept over power-off) servo offsets");
  offset->require_subcommand(1);

  auto read = std::make_shared<Options>();
  CLI::App* read_cmd =
      offset->add_subcommand("read", "Print servo offsets as a table (ServoOffsetRead)");
  read_cmd->add_option("SERVO", read->servos, "Servo ids (or names with --robot)")->required();
  add_robot_option(*read_cmd, read->robot);
  add_device_options(*read_cmd, read->device);
  read_cmd->callback([read, &ctx, &result] { result.code = read_offsets(ctx, *read); });

  auto adjust = std::make_shared<Options>();
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

  auto write = std::make_shared<Options>();
  CLI::App* write_cmd = offset->add_subcommand(
      "write", "Keep servos' current offsets over power-off (ServoOffsetWrite)");
  write_cmd->add_option("SERVO", write->servos, "Servo ids (or names with --robot)")->required();
  add_robot_option(*write_cmd, write->robot);
  add_device_options(*write_cmd, write->device);
  write_cmd->callback([write, &ctx, &result] { result.code = write_offsets(ctx, *write); });
}

}  // namespace seqc::cli
