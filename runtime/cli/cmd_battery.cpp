// `seqc battery`: the servo controller's supply voltage (GetBatteryVoltage).
#include <cstdint>
#include <memory>
#include <ostream>
#include <string>

#include <CLI/CLI.hpp>

#include "runtime/cli/commands.hpp"
#include "runtime/cli/device_command.hpp"

namespace seqc::cli {
namespace {

// "7500 mV (7.50 V)": volts rounded to the nearest 10 mV.
std::string format_voltage(std::uint16_t millivolts) {
  const unsigned centivolts = (unsigned{millivolts} + 5) / 10;
  const unsigned hundredths = centivolts % 100;
  return std::to_string(millivolts) + " mV (" + std::to_string(centivolts / 100) + "." +
         (hundredths < 10 ? "0" : "") + std::to_string(hundredths) + " V)";
}

}  // namespace

void add_battery_command(CLI::App& app, Context& ctx, Outcome& result) {
  auto device = std::make_shared<DeviceOptions>();
  CLI::App* cmd = app.add_subcommand(
      "battery", "Print the servo controller's supply voltage (GetBatteryVoltage)");
  add_device_options(*cmd, *device);
  cmd->callback([device, &ctx, &result] {
    result.code = run_on_controller(ctx, *device, [&](boards::XarmSession& s) {
      auto v = s.ask<lsc::BatteryVoltage>(lsc::GetBatteryVoltage{}, "the battery voltage");
      if (!v) return ExitCode::DeviceFailure;
      ctx.out << format_voltage(v->millivolts) << "\n";
      return ExitCode::Ok;
    });
  });
}

}  // namespace seqc::cli
