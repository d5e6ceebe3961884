// `seqc calibrate clock [--port P] [--group N] [--runs K] [--length TIME]`: how fast the board's
// own clock runs against the computer's (runtime/boards/clock_calibration.hpp), printed as ppm
// with its spread and as the line a rig file takes (docs/music.md, "Long songs: the board's
// clock").
#include <cmath>
#include <cstdint>
#include <memory>
#include <ostream>
#include <string>

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include "base/units.hpp"
#include "runtime/boards/board.hpp"
#include "runtime/boards/clock_calibration.hpp"
#include "runtime/cli/board_text.hpp"
#include "runtime/cli/commands.hpp"
#include "runtime/cli/device_command.hpp"
#include "runtime/io/time_text.hpp"
#include "runtime/upload/uploader.hpp"

namespace seqc::cli {
namespace {

struct ClockArgs {
  DeviceOptions device;
  int group = 254;
  int runs = 5;
  std::string length = "20s";
};

// "+7,985", "-10,000", "0".
std::string signed_ppm(long long ppm) { return (ppm > 0 ? "+" : "") + seqc::format_grouped(ppm); }

ExitCode run_clock(Context& ctx, const ClockArgs& a) {
  auto length = boards::parse_run_length(a.length);
  if (!length) return usage_error(ctx, length.error().message);
  const boards::Board& board = boards::board_for_command(a.device.profile(), a.device.port);
  if (board.time_run == nullptr || board.plan == nullptr) {
    return refuse_command(ctx, board, a.device.command);
  }
  boards::ClockSettings settings;
  settings.group = static_cast<std::uint8_t>(a.group);
  settings.runs = static_cast<std::size_t>(a.runs);
  settings.run_ms = *length;
  return run_on_board(ctx, a.device, board, [&](const boards::Line& line, const std::string& port) {
    if (ctx.verbosity >= 0) {
      ctx.err << "seqc: storing " << io::seconds_text(std::chrono::milliseconds(*length))
              << " of held servos in group " << a.group << ", then timing " << a.runs
              << (a.runs == 1 ? " run" : " runs") << " (about "
              << io::duration_text(std::chrono::milliseconds(*length) * a.runs) << ")\n";
    }
    const boards::ClockMeasurement m = boards::measure_clock(board, line, settings);
    if (!m.upload.ok()) {
      ctx.err << "seqc: error: " << m.upload.message << "\n"
              << "seqc: " << upload::describe_group_state(m.upload.group_state, settings.group)
              << "\n";
      return exit_code_for(m.upload.status);
    }
    if (!m.failure.ok()) return report_outcome(ctx, m.failure, line, port, board);
    if (!m.positions_read && ctx.verbosity >= 0) {
      if (m.held.empty()) {
        ctx.err << "seqc: note: " << board.called
                << " cannot say where its servos are, so the measuring actions named none\n";
      } else {
        ctx.err << "seqc: warning: " << board.called
                << " did not say where its servos are; the measuring group held them at "
                << settings.fallback_position << "\n";
      }
    }
    if (ctx.verbosity > 0) {
      for (std::size_t i = 0; i < m.lasted.size(); ++i) {
        ctx.err << fmt::format("run {}: {} -> {} ppm\n", i + 1, io::seconds_text(m.lasted[i], 6),
                               signed_ppm(std::llround(m.ppm[i])));
      }
    }
    const long long ppm = std::llround(m.mean_ppm);
    ctx.out << "clock: " << signed_ppm(ppm) << " ppm \u00b1 "
            << seqc::format_grouped(std::llround(std::ceil(m.spread_ppm))) << " (" << m.ppm.size()
            << (m.ppm.size() == 1 ? " run" : " runs") << " of "
            << io::seconds_text(std::chrono::milliseconds(*length)) << ")\n";
    ctx.out << "rig file (--rig): clock_ppm: " << (ppm > 0 ? "+" : "") << ppm << "\n";
    return ExitCode::Ok;
  });
}

}  // namespace

void add_calibrate_command(CLI::App& app, Context& ctx, Outcome& result) {
  CLI::App* cmd = app.add_subcommand("calibrate", "Measure the board against the computer");
  cmd->require_subcommand(1);
  auto a = std::make_shared<ClockArgs>();
  CLI::App* clock = cmd->add_subcommand(
      "clock",
      "How fast the board's own clock runs, in ppm: stores a group of known length (holding the "
      "servos where they are), times several runs of it, prints the line for a rig file");
  clock
      ->add_option("--group", a->group,
                   "Group to store the measuring actions in; it is overwritten (0-254, default "
                   "254)")
      ->check(CLI::Range(0, 254));
  clock->add_option("--runs", a->runs, "How many runs to time (1-100, default 5)")
      ->check(CLI::Range(1, 100));
  clock->add_option("--length", a->length, "One run's length on the board's clock (1s-10min)")
      ->capture_default_str();
  add_device_options(*clock, a->device);
  clock->callback([&ctx, &result, a] { result.code = run_clock(ctx, *a); });
}

}  // namespace seqc::cli
