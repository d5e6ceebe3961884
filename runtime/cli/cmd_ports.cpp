// seqc ports [--json | --names]: the serial ports, on-board UARTs and xArm HID devices a
// controller could be on. The plain listing is for people (exit 3 with hints when nothing is
// found); --json and --names are for programs and shell completion: they print the list, empty
// or not, and exit 0.
#include <CLI/CLI.hpp>

#include "runtime/cli/commands.hpp"
#include "runtime/transport/hidapi_backend.hpp"
#include "runtime/transport/port_discovery.hpp"

namespace seqc::cli {

void add_ports_command(CLI::App& app, Context& ctx, Outcome& result) {
  struct Options {
    bool json = false;
    bool names = false;
  };
  auto opts = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand(
      "ports", "List the serial ports and USB HID controllers seqc can use (for --port)");
  CLI::Option* json =
      cmd->add_flag("--json", opts->json, "Print a JSON array (port, kind, device, USB strings)");
  cmd->add_flag("--names", opts->names, "Print only what --port takes, one per line")
      ->excludes(json);
  cmd->callback([&ctx, &result, opts] {
    transport::HidapiBackend hid;
    transport::SystemDeviceLister lister(hid);
    transport::Discovery found = transport::discover_ports(lister);
    if (ctx.verbosity >= 0) {
      for (const std::string& w : found.warnings) ctx.err << "seqc: warning: " << w << "\n";
    }
    result.code = ExitCode::Ok;
    if (opts->json) {
      ctx.out << transport::format_port_json(found.candidates);
      return;
    }
    if (opts->names) {
      for (const auto& c : found.candidates) ctx.out << transport::format_port(c.spec()) << "\n";
      return;
    }
    if (found.candidates.empty()) {
      ctx.err << "seqc: error: " << transport::no_controller_message() << "\n";
      result.code = ExitCode::PortUnavailable;
      return;
    }
    ctx.out << transport::format_port_list(found.candidates);
  });
}

}  // namespace seqc::cli
