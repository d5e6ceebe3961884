#include "runtime/cli/port_open.hpp"

#include <utility>

#include "runtime/emulator/emulator_transport.hpp"
#include "runtime/emulator/hid_face.hpp"
#include "runtime/transport/baud_rates.hpp"
#include "runtime/transport/hidapi_backend.hpp"
#include "runtime/transport/open_port.hpp"
#include "runtime/transport/port_discovery.hpp"
#include "runtime/transport/port_spec.hpp"

namespace seqc::cli {
namespace {

// The servo controllers' UART rate (docs/protocol/servo-controller.md, Framing).
constexpr std::uint32_t kEmulatedBaud = 9600;

PortOpenResult failure(ExitCode code, std::string message) {
  PortOpenResult r;
  r.failure = PortFailure{code, std::move(message)};
  return r;
}

PortOpenResult open_lsc6(const transport::PortSpec& spec, Context& ctx) {
  OpenedPort port;
  if (ctx.lsc6_emulator != nullptr && ctx.xarm_clock != nullptr) {
    port.transport = std::make_unique<emu::EmulatorTransport>(*ctx.lsc6_emulator, *ctx.xarm_clock);
    port.clock = ctx.xarm_clock;
  } else {
    emu::Lsc6Config config;
    if (auto ok = emu::apply_lsc6_options(spec.emulator_options, config); !ok) {
      return failure(ExitCode::Usage,
                     "--port " + transport::format_port(spec) + ": " + ok.error().message);
    }
    port.emulated_clock = std::make_unique<io::ManualClock>();
    port.lsc6_emulator = std::make_unique<emu::Lsc6Emulator>(config);
    port.transport =
        std::make_unique<emu::EmulatorTransport>(*port.lsc6_emulator, *port.emulated_clock);
    port.clock = port.emulated_clock.get();
  }
  PortOpenResult r;
  r.port = std::move(port);
  return r;
}

// A fresh XArmEmulator on its own clock, with the spec's options over `baud` (no transport yet).
PortOpenResult new_xarm_emulator(const transport::PortSpec& spec, std::uint32_t baud) {
  emu::XArmConfig config;
  config.baud = baud;
  if (auto ok = emu::apply_emulator_options(spec.emulator_options, config); !ok) {
    return failure(ExitCode::Usage,
                   "--port " + transport::format_port(spec) + ": " + ok.error().message);
  }
  PortOpenResult r;
  r.port.emplace();
  r.port->emulated_clock = std::make_unique<io::ManualClock>();
  r.port->emulator = std::make_unique<emu::XArmEmulator>(config);
  r.port->clock = r.port->emulated_clock.get();
  return r;
}

// The xArm emulator behind its USB HID face: discovery and HidTransport as for a real device.
PortOpenResult open_xarm_hid(const transport::PortSpec& spec) {
  // No UART on this path: reports are paced by the USB frames.
  PortOpenResult made = new_xarm_emulator(spec, 0);
  if (!made.port) return made;
  OpenedPort& port = *made.port;
  emu::EmulatedHidBackend backend(*port.emulator, *port.emulated_clock);
  auto opened =
      transport::open_port(transport::hid_port(), *port.emulated_clock, kEmulatedBaud, backend);
  if (!opened) return failure(ExitCode::PortUnavailable, opened.error().message);
  port.transport = std::move(opened).value();
  return made;
}

PortOpenResult open_emulator(const transport::PortSpec& spec, Context& ctx) {
  if (spec.emulator == "lsc6") return open_lsc6(spec, ctx);
  if (spec.emulator == "xarm-hid") return open_xarm_hid(spec);
  if (spec.emulator != "xarm") {
    return failure(ExitCode::Usage, "--port emu:" + spec.emulator +
                                        ": this command talks to the servo controller; use "
                                        "emu:xarm or emu:lsc6");
  }
  if (ctx.xarm_emulator != nullptr && ctx.xarm_clock != nullptr) {
    // The caller's emulator (Context::xarm_emulator); its own config holds any faults.
    OpenedPort port;
    port.transport = std::make_unique<emu::EmulatorTransport>(*ctx.xarm_emulator, *ctx.xarm_clock);
    port.clock = ctx.xarm_clock;
    PortOpenResult r;
    r.port = std::move(port);
    return r;
  }
  // Paced like the real line (and `seqc emulate xarm`), so times and rates are the wire's;
  // `emu:xarm?baud=0` runs unpaced.
  PortOpenResult made = new_xarm_emulator(spec, kEmulatedBaud);
  if (made.port) {
    OpenedPort& port = *made.port;
    port.transport = std::make_unique<emu::EmulatorTransport>(*port.emulator, *port.emulated_clock);
  }
  return made;
}

}  // namespace

PortOpenResult open_controller_port(const std::string& port_text, Context& ctx) {
  transport::PortSpec spec;
  if (port_text.empty()) {
    transport::HidapiBackend hid;
    transport::SystemDeviceLister lister(hid);
    const transport::Discovery found = transport::discover_ports(lister);
    auto chosen = transport::select_default_port(found.candidates);
    if (!chosen) return failure(ExitCode::PortUnavailable, chosen.error().message);
    spec = chosen->spec();
  } else {
    auto parsed = transport::parse_port(port_text);
    if (!parsed) return failure(ExitCode::Usage, "--port: " + parsed.error().message);
    spec = *parsed;
  }
  if (spec.kind == transport::PortKind::Emulator) return open_emulator(spec, ctx);

  auto opened = transport::open_port(spec, ctx.clock, transport::kDefaultBaud);
  if (!opened) return failure(ExitCode::PortUnavailable, opened.error().message);
  OpenedPort port;
  port.transport = std::move(opened).value();
  port.clock = &ctx.clock;
  PortOpenResult r;
  r.port = std::move(port);
  return r;
}

}  // namespace seqc::cli
