// seqc ports: the serial ports and xArm HID devices a controller could be on.
#include "runtime/cli/commands.hpp"
#include "runtime/transport/hidapi_backend.hpp"
#include "runtime/transport/port_discovery.hpp"

namespace seqc::cli {

void add_ports_command(CLI::App& app, Context& ctx, Outcome& result) {
  CLI::App* cmd = app.add_subcommand(
      "ports", "List the serial ports and USB HID controllers seqc can use (for --port)");
  cmd->callback([&ctx, &result] {
    transport::HidapiBackend hid;
    transport::SystemDeviceLister lister(hid);
    transport::Discovery found = transport::discover_ports(lister);
    for (const std::string& w : found.warnings) ctx.err << "seqc: warning: " << w << "\n";
    if (found.candidates.empty()) {
      ctx.err << "seqc: error: " << transport::no_controller_message() << "\n";
      result.code = ExitCode::PortUnavailable;
      return;
    }
    ctx.out << transport::format_port_list(found.candidates);
    result.code = ExitCode::Ok;
  });
}

}  // namespace seqc::cli
