// `seqc bus-info read|write`: a bus servo's limits and state (BusServoInfoRead,
// BusServoInfoWrite).
//
// BusServoInfoWrite is not addressed: every servo on the bus takes what it carries, at once
// (docs/protocol/servo-controller.md). `write` therefore refuses to run unless the user states,
// with --i-have-one-servo-attached, that only the servo to configure is connected. Fields the
// user does not give keep that servo's values (boards::write_bus_servo_info reads it first).
#include <memory>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "runtime/boards/reading_table.hpp"
#include "runtime/boards/xarm_queries.hpp"
#include "runtime/cli/commands.hpp"
#include "runtime/cli/device_args.hpp"
#include "runtime/cli/device_command.hpp"

namespace seqc::cli {
namespace {

constexpr const char* kConfirmFlag = "--i-have-one-servo-attached";

// ---- read ----------------------------------------------------------------------------------

ExitCode read_info(Context& ctx, const DeviceOptions& device) {
  return run_on_controller(ctx, device, [&](boards::XarmSession& s) {
    auto info = s.ask<lsc::BusServoInfo>(lsc::BusServoInfoRead{}, "the bus servo info");
    if (!info) return ExitCode::DeviceFailure;
    ctx.out << boards::bus_servo_limits_table(info->id, info->limits) << "\n"
            << boards::bus_servo_state_table(*info);
    return ExitCode::Ok;
  });
}

// ---- write ---------------------------------------------------------------------------------

struct WriteOptions {
  DeviceOptions device;
  bool one_servo = false;
  boards::BusServoFields fields;
};

ExitCode write_info(Context& ctx, const WriteOptions& o) {
  if (!o.one_servo) {
    return usage_error(ctx,
                       std::string("bus-info write is not addressed to one servo: every servo on "
                                   "the bus takes these settings at once. Disconnect all servos "
                                   "but the one to configure, then add ") +
                           kConfirmFlag);
  }
  auto changes = boards::checked_changes(o.fields);
  if (!changes) return usage_error(ctx, changes.error().message);
  return run_on_controller(ctx, o.device, [&](boards::XarmSession& s) {
    const boards::BusServoWrite w = boards::write_bus_servo_info(s, *changes);
    if (w.conflict != boards::LimitConflict::None) {
      return usage_error(ctx, boards::conflict_text(w.write.limits) +
                                  " (after merging with the servo's current settings); nothing "
                                  "written");
    }
    if (!w.written) return ExitCode::DeviceFailure;
    summarize(ctx, "written to every servo on the bus (kept over power-off):");
    ctx.out << boards::bus_servo_limits_table(w.write.servo, w.write.limits);
    return ExitCode::Ok;
  });
}

}  // namespace

void add_bus_info_command(CLI::App& app, Context& ctx, Outcome& result) {
  CLI::App* bus = app.add_subcommand(
      "bus-info", "Read or write a bus servo's limits (id, position, voltage, temperature, LED)");
  bus->require_subcommand(1);

  auto read = std::make_shared<DeviceOptions>();
  CLI::App* read_cmd = bus->add_subcommand(
      "read",
      "Print the limits and state of the bus servo that answers (BusServoInfoRead; on a bus\n"
      "with several servos the controller answers for one of them)");
  add_device_options(*read_cmd, *read);
  read_cmd->callback([read, &ctx, &result] { result.code = read_info(ctx, *read); });

  auto w = std::make_shared<WriteOptions>();
  CLI::App* write_cmd = bus->add_subcommand(
      "write",
      "Set bus servo limits (BusServoInfoWrite; kept over power-off). It is not addressed:\n"
      "EVERY servo on the bus takes these values at once, so it runs only with\n"
      "--i-have-one-servo-attached. Fields not given keep the attached servo's values");
  write_cmd->add_flag(kConfirmFlag, w->one_servo,
                      "Confirm that exactly one servo is connected to the bus");
  write_cmd->add_option("--servo", w->fields.servo, "Servo id field (0-255)");
  write_cmd->add_option("--position-min", w->fields.position_min, "Lowest position (0-65535)");
  write_cmd->add_option("--position-max", w->fields.position_max, "Highest position (0-65535)");
  write_cmd->add_option("--millivolts-min", w->fields.millivolts_min, "Lowest supply voltage, mV");
  write_cmd->add_option("--millivolts-max", w->fields.millivolts_max, "Highest supply voltage, mV");
  write_cmd->add_option("--temp-max", w->fields.temp_max, "Highest temperature, degrees C");
  write_cmd->add_option("--led", w->fields.led, "Status LED: on or off")
      ->check(CLI::IsMember({"on", "off"}));
  write_cmd->add_option("--led-warning", w->fields.led_warning,
                        "Faults the LED flashes for: overheat,overvoltage,overposition "
                        "(any) or none");
  add_device_options(*write_cmd, w->device);
  write_cmd->callback([w, &ctx, &result] { result.code = write_info(ctx, *w); });
}

}  // namespace seqc::cli
