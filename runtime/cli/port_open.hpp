// Turns `--port` (or its absence) into a Transport and the clock to use with it, for every
// command that talks to the servo controller (upload, group, battery, servo, ...).
//
//   --port emu:xarm[?FAULTS]  an in-process XArmEmulator (FAULTS as `seqc emulate --faults`),
//   --port emu:lsc6[?OPTS]    or Lsc6Emulator (OPTS as `seqc emulate lsc6 --faults`),
//                             driven through EmulatorTransport on a ManualClock: the command
//                             runs in emulated time and finishes at once
//   --port PATH / hid / ...   transport::open_port with ctx.clock (real time), 9600 baud by
//                             default
//   no --port                 the one controller discovery finds (transport::discover_ports
//                             and select_default_port)
// Errors: a malformed --port is a usage error (2); a port that cannot be opened or found is
// PortUnavailable (3). Messages are ready for "seqc: error: ".
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "runtime/cli/context.hpp"
#include "runtime/cli/exit_codes.hpp"
#include "runtime/emulator/lsc6_emulator.hpp"
#include "runtime/emulator/xarm_emulator.hpp"
#include "runtime/io/clock.hpp"
#include "runtime/io/transport.hpp"

namespace seqc::cli {

struct OpenedPort {
  std::unique_ptr<io::Transport> transport;
  io::Clock* clock = nullptr;  // use this clock with the transport (and for everything timed)
  // emu:xarm only: the emulated controller and its clock (tests look at what it stored).
  std::unique_ptr<io::ManualClock> emulated_clock;
  std::unique_ptr<emu::XArmEmulator> emulator;
  // emu:lsc6 only: the emulated LSC-6 board.
  std::unique_ptr<emu::Lsc6Emulator> lsc6_emulator;

  bool emulated() const { return emulator != nullptr || lsc6_emulator != nullptr; }
};

struct PortFailure {
  ExitCode code = ExitCode::PortUnavailable;
  std::string message;
};

struct PortOpenResult {
  std::optional<OpenedPort> port;
  PortFailure failure;  // when !port
};

// `port` empty: discovery. Only the servo controller's ports (emu:raspblock is refused).
PortOpenResult open_controller_port(const std::string& port, Context& ctx);

}  // namespace seqc::cli
