#include "runtime/cli/board_port.hpp"

#include "runtime/protocol/raspblock.hpp"
#include "runtime/transport/open_port.hpp"
#include "runtime/transport/port_spec.hpp"

namespace seqc::cli {
namespace {

// The board never replies; writes go to the emulator at the clock's time since opening.
class BoardTransport final : public io::Transport {
 public:
  BoardTransport(emu::RaspblockEmulator& board, io::Clock& clock)
      : board_(board), clock_(clock), origin_(clock.now()) {}
  Status write(ByteView bytes) override {
    board_.receive(bytes, clock_.now() - origin_);
    return Ok{};
  }
  io::ReadResult read(std::span<std::uint8_t>, io::TimePoint deadline) override {
    clock_.sleep_until(deadline);
    return {io::ReadStatus::Timeout, 0, {}};
  }
  void discard_input() override {}
  std::string describe() const override { return "emu:raspblock"; }

 private:
  emu::RaspblockEmulator& board_;
  io::Clock& clock_;
  io::TimePoint origin_;
};

}  // namespace

Result<OpenedBoard> open_board_port(const std::string& port, const std::string& what, Context& ctx,
                                    ExitCode& code) {
  code = ExitCode::Usage;
  auto spec = transport::parse_port(port);
  if (!spec) return make_error("--port: " + spec.error().message);
  OpenedBoard out;
  if (spec->kind == transport::PortKind::Emulator) {
    if (spec->emulator != "raspblock") {
      return make_error("--port " + port + " is the servo controller's emulator; " + what +
                        " is for the raspblock (use --port emu:raspblock)");
    }
    out.emulator = std::make_unique<emu::RaspblockEmulator>();
    out.link = std::make_unique<BoardTransport>(*out.emulator, ctx.clock);
    return out;
  }
  if (spec->kind == transport::PortKind::Hid) {
    return make_error("--port " + port +
                      " is a USB HID device (the xArm's link); the Raspblock board is reached "
                      "over a serial port at 115200 baud");
  }
  auto opened = transport::open_port(*spec, ctx.clock, raspblock::kBaud);
  if (!opened) {
    code = ExitCode::PortUnavailable;
    return opened.error();
  }
  out.link = std::move(*opened);
  return out;
}

}  // namespace seqc::cli
