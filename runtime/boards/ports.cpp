#include "runtime/boards/ports.hpp"

#include <utility>

#include "runtime/transport/hidapi_backend.hpp"
#include "runtime/transport/open_port.hpp"
#include "runtime/transport/port_spec.hpp"

namespace seqc::boards {
namespace {

// A serial port's rate when the command names no board: the servo controllers'.
constexpr std::uint32_t kServoControllerBaud = 9600;

OpenResult failure(PortProblem problem, std::string detail, const Board* reached = nullptr) {
  OpenResult r;
  r.failure = PortFailure{problem, std::move(detail), reached};
  return r;
}

OpenResult opened(OpenedPort port) {
  OpenResult r;
  r.port = std::move(port);
  return r;
}

// The one port discovery finds, or why there is not exactly one.
Result<transport::PortSpec> discover(const Hooks& hooks) {
  if (hooks.lister != nullptr) {
    auto chosen =
        transport::select_default_port(transport::discover_ports(*hooks.lister).candidates);
    if (!chosen) return chosen.error();
    return chosen->spec();
  }
  transport::HidapiBackend hid;
  const transport::SystemDeviceLister lister(hid);
  auto chosen = transport::select_default_port(transport::discover_ports(lister).candidates);
  if (!chosen) return chosen.error();
  return chosen->spec();
}

// Any servo controller when the command names no board.
bool fits(const Board* wanted, const Board& reached) {
  if (wanted != nullptr) return same_family(*wanted, reached);
  for (const Board* b : all_boards()) {
    if (b->discoverable && same_family(*b, reached)) return true;
  }
  return false;
}

}  // namespace

OpenResult open_port(const PortRequest& request, io::Clock& clock, const Hooks& hooks) {
  const Board* board = request.board;
  transport::PortSpec spec;
  if (request.text.empty()) {
    if (board != nullptr && !board->discoverable) return failure(PortProblem::NeedsPort, "");
    auto found = discover(hooks);
    if (!found) return failure(PortProblem::NotFound, found.error().message);
    spec = *found;
  } else {
    auto parsed = transport::parse_port(request.text);
    if (!parsed) return failure(PortProblem::Malformed, parsed.error().message);
    spec = *parsed;
  }

  if (spec.kind == transport::PortKind::Emulator) {
    const Board* reached = board_for_emulator(spec.emulator);
    if (reached == nullptr || reached->open_emulator == nullptr) {
      return failure(PortProblem::Malformed, "no board answers to emu:" + spec.emulator);
    }
    if (!fits(board, *reached)) return failure(PortProblem::WrongEmulator, "", reached);
    OpenedPort port;
    std::string error;
    if (!reached->open_emulator(spec, clock, hooks, port, error)) {
      return failure(PortProblem::EmulatorOptions, error, reached);
    }
    // An emulator that was made but whose transport could not be opened (emu:xarm-hid).
    if (port.transport == nullptr) return failure(PortProblem::CannotOpen, error, reached);
    port.board = reached;
    return opened(std::move(port));
  }

  if (spec.kind == transport::PortKind::Hid && board != nullptr && !board->over_hid) {
    return failure(PortProblem::WrongKind, "");
  }
  auto transport =
      transport::open_port(spec, clock, board != nullptr ? board->baud : kServoControllerBaud);
  if (!transport) return failure(PortProblem::CannotOpen, transport.error().message);
  OpenedPort port;
  port.transport = std::move(transport).value();
  port.clock = &clock;
  port.board = board;
  return opened(std::move(port));
}

std::optional<Received> received(const OpenedPort& port) {
  if (!port.raspblock) return std::nullopt;
  return Received{port.raspblock->packets().size(), port.raspblock->rejections().size()};
}

}  // namespace seqc::boards
