// Opening any port a command names: a serial device, `hid`, discovery when no --port is given,
// or an in-process emulator (emu:NAME). What differs per board (default baud, whether HID or
// discovery reach it, how its emulator is built) comes from the Board row; this file holds the
// order of the checks. It returns a status and the words of the layer that failed, never a
// sentence for people: the CLI words PortProblem and picks the exit code. OpenedPort owns every
// object the transport uses (the emulated clock, the emulator, the HID backend), so a port
// stays valid for as long as the caller keeps it.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "runtime/boards/board.hpp"
#include "runtime/boards/hooks.hpp"
#include "runtime/emulator/controller_device.hpp"
#include "runtime/emulator/lsc6_emulator.hpp"
#include "runtime/emulator/raspblock_emulator.hpp"
#include "runtime/emulator/xarm_emulator.hpp"
#include "runtime/io/clock.hpp"
#include "runtime/io/transport.hpp"
#include "runtime/transport/hid_backend.hpp"
#include "runtime/transport/port_discovery.hpp"

namespace seqc::boards {

struct PortRequest {
  std::string text;  // --port as given; "" = discovery
  // What the command talks to: default baud, HID and discovery policy, which emulators fit
  // (same family); null = any servo controller.
  const Board* board = nullptr;
};

enum class PortProblem {
  Malformed,        // detail = transport::parse_port's words                 -> Usage
  EmulatorOptions,  // detail = the emulator's option parser's words           -> Usage
  WrongEmulator,    // emu:NAME reaches another family (failure.reached)       -> Usage
  WrongKind,        // `hid` for a board without over_hid                     -> Usage
  NeedsPort,        // no --port, and the board cannot be discovered           -> Usage
  NotFound,         // discovery found none or several; detail = its words     -> PortUnavailable
  CannotOpen,       // detail = transport::open_port's words                   -> PortUnavailable
};

struct PortFailure {
  PortProblem problem = PortProblem::CannotOpen;
  std::string detail;
  const Board* reached = nullptr;
};

struct OpenedPort {
  // Emulator state first: members are destroyed in reverse order, so the transport goes first.
  std::unique_ptr<io::ManualClock> emulated_clock;
  std::unique_ptr<emu::ControllerDevice> controller;   // emu:xarm[-hid], emu:lsc6 made here
  std::unique_ptr<emu::RaspblockEmulator> raspblock;   // emu:raspblock
  std::shared_ptr<transport::HidBackend> hid_backend;  // emu:xarm-hid: must outlive the transport
  std::unique_ptr<io::Transport> transport;
  io::Clock* clock = nullptr;  // the clock to use with `transport` (the emulated one for emu:*)
  // The board at the far end when the port says so (emu:NAME), else request.board.
  const Board* board = nullptr;
  bool emulated = false;

  // The transport runs on a clock of the port's own: an in-process emulator in emulated time,
  // which jumps to whatever instant is waited for. No instant on it can be compared with the
  // host's clock or an audio output's (emu:raspblock, stamped on the caller's clock, can).
  bool own_clock() const { return emulated_clock != nullptr; }
};

struct OpenResult {
  std::optional<OpenedPort> port;
  PortFailure failure;
};

OpenResult open_port(const PortRequest& request, io::Clock& clock, const Hooks& hooks = {});

// What the board behind an emulated port received, for emulators that count what they take and
// refuse (emu:raspblock's packets); nullopt for every other port.
struct Received {
  std::size_t packets = 0;
  std::size_t rejected = 0;
};
std::optional<Received> received(const OpenedPort& port);

}  // namespace seqc::boards
