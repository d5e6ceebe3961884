// `seqc battery`: the servo controller's supply voltage (GetBatteryVoltage).
#include <memory>
#include <ostream>
#include <string>

#include <CLI/CLI.hpp>

#include "runtime/boards/reading_table.hpp"
#include "runtime/cli/commands.hpp"
#include "runtime/cli/device_command.hpp"

namespace seqc::cli {

void add_battery_command(CLI::App& app, Context& ctx, Outcome& result) {
  auto device = std::make_shared<DeviceOptions>();
  CLI::App* cmd = app.add_subcommand(
      "battery", "Print the servo controller's supply voltage (GetBatteryVoltage)");
  add_device_options(*cmd, *device);
  cmd->callback([device, &ctx, &result] {
    result.code = run_on_controller(ctx, *device, [&](boards::XarmSession& s) {
      auto v = s.ask<lsc::BatteryVoltage>(lsc::GetBatteryVoltage{}, "the battery voltage");
      if (!v) return ExitCode::DeviceFailure;
      ctx.out << boards::voltage_text(v->millivolts) << "\n";
      return ExitCode::Ok;
    });
  });
}

}  // namespace seqc::cli
