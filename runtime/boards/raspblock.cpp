// The Raspblock car board: it stores nothing and answers nothing. Its program is a timed packet
// stream played live at 115200 baud over a serial port; after an early end it gets the frame
// that stops the car. Reached in process as emu:raspblock, stamped with the caller's clock.
#include <memory>
#include <string>
#include <utility>

#include "compiler/formats/raspblock_listing.hpp"
#include "compiler/targets/raspblock/raspblock_stream.hpp"
#include "runtime/boards/board.hpp"
#include "runtime/boards/ports.hpp"
#include "runtime/emulator/raspblock_transport.hpp"
#include "protocol/raspblock/raspblock.hpp"

namespace seqc::boards {
namespace {

constexpr std::string_view kEmulators[] = {"raspblock"};

Result<std::vector<compiler::StreamFrame>> stream_of(const compiler::CompileOutput& output) {
  const compiler::RaspblockProgram* car = output.raspblock_program();
  if (car == nullptr) return make_error("the program is not a Raspblock program");
  return compiler::plan_stream(*car);
}

// The stream has no group: `group` does not apply.
Result<std::string> render(const compiler::CompileOutput& output, Emit emit,
                           std::uint8_t /*group*/) {
  auto frames = stream_of(output);
  if (!frames) return frames.error();
  const compiler::RaspblockProgram& car = *output.raspblock_program();
  switch (emit) {
    case Emit::Hex:
      return compiler::render_stream_hex(*frames);
    case Emit::Listing:
      return compiler::render_stream_listing(car, *frames, output.sources);
    case Emit::Json:
      return compiler::render_stream_json(car, *frames);
  }
  return make_error("unknown output form");
}

Result<std::vector<player::ScheduledFrame>> live_frames(const compiler::CompileOutput& output) {
  auto frames = stream_of(output);
  if (!frames) return frames.error();
  std::vector<player::ScheduledFrame> out;
  for (compiler::StreamFrame& f : *frames) {
    out.push_back({std::chrono::milliseconds(f.at_ms), std::move(f.bytes)});
  }
  return out;
}

bool open_emulator(const transport::PortSpec& /*spec*/, io::Clock& host, const Hooks& /*hooks*/,
                   OpenedPort& out, std::string& /*error*/) {
  // The board never replies, so it needs no emulated time: writes are stamped on the caller's.
  out.raspblock = std::make_unique<emu::RaspblockEmulator>();
  out.transport = std::make_unique<emu::RaspblockTransport>(*out.raspblock, host);
  out.clock = &host;
  out.emulated = true;
  return true;
}

}  // namespace

extern const Board kRaspblockBoard;
const Board kRaspblockBoard = {
    .key = "raspblock",
    .name = "Raspblock",
    .called = "the board",
    .family = "Raspblock board",
    .dialect = &kRaspblockDialect,
    .baud = raspblock::kBaud,
    .over_hid = false,
    .discoverable = false,
    .render = render,
    .plan = nullptr,
    .upload = nullptr,
    .acknowledge = nullptr,
    .comment = nullptr,
    .unconfirmed_run = "",
    .live_frames = live_frames,
    .probe = nullptr,
    .safe_stop = compiler::stop_frame,
    .measure_departure = false,
    .check_schedule = false,
    .wait_for_end = false,
    .style = LiveStyle::Stream,
    .unprobed_note = "",
    .run_name = "",
    .run_frame = nullptr,
    .confirm_run = nullptr,
    .run_note = "",
    .stop_frame = nullptr,
    .stop = nullptr,
    .erase = nullptr,
    .erases_one_group = false,
    .move = nullptr,
    .confirms_moves = false,
    .queries = false,
    .pose_profile = "",
    .lacks = "",
    .emulators = kEmulators,
    .open_emulator = open_emulator,
    .serve = emu::serve_raspblock,
    .emulator_options = kBaud,
    .no_faults_reason = "the Raspblock board never replies",
    .no_groups_reason = "the Raspblock board stores no groups",
};

}  // namespace seqc::boards
