// seqc play FILE [--port P] [--strict]: streams a compiled sequence to a device that keeps no
// program, sending each frame at its time on the host's clock (runtime/player).
//
// The Raspblock car board, and the servo controller (xArm / LSC) without storing a group
// (play_servo_program, servo_play.hpp).
#include <atomic>
#include <cstdio>
#include <memory>
#include <ostream>
#include <string>

#include "compiler/backend/raspblock_stream.hpp"
#include "compiler/source/units.hpp"
#include "runtime/cli/board_port.hpp"
#include "runtime/cli/commands.hpp"
#include "runtime/cli/compile_report.hpp"
#include "runtime/cli/play_progress.hpp"
#include "runtime/cli/servo_play.hpp"
#include "runtime/emulator/raspblock_emulator.hpp"
#include "runtime/io/realtime.hpp"
#include "runtime/player/player.hpp"
#include "runtime/protocol/raspblock.hpp"
#include "runtime/transport/open_port.hpp"
#include "runtime/transport/port_spec.hpp"

namespace seqc::cli {
namespace {

struct PlayOptions {
  std::string file;
  std::string port;
  bool strict = false;
  bool realtime = false;
  bool allow_late = false;
};

std::string ms_text(io::Duration d) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f ms", std::chrono::duration<double, std::milli>(d).count());
  return buf;
}

// The servo controller (xArm / LSC) streamed live, one MultiServoMove per keyframe
// (servo_play.hpp); --port as for `seqc upload`, default discovery.
ExitCode play_servo_program(const compiler::CompileOutput& output, const PlayOptions& o,
                            Context& ctx) {
  DeviceOptions device;
  device.port = o.port;
  device.command = "play";
  return play_on_servo_controller(ctx, output, device, LivePlayOptions{o.file, o.allow_late});
}

ExitCode play_raspblock(const compiler::RaspblockProgram& program, const PlayOptions& o,
                        Context& ctx) {
  auto frames = backend::plan_stream(program);
  if (!frames) {
    ctx.err << "seqc: error: " << frames.error().message << "\n";
    return ExitCode::Internal;
  }
  if (o.port.empty()) {
    ctx.err << "seqc: error: name the board's serial port with --port, e.g. --port /dev/ttyAMA0 "
               "or --port ttyUSB0 (the board does not announce itself)\n"
               "  hint: --port emu:raspblock plays to the built-in board emulator\n";
    return ExitCode::Usage;
  }
  ExitCode open_code = ExitCode::Ok;
  auto opened = open_board_port(o.port, o.file, ctx, open_code);
  if (!opened) {
    ctx.err << "seqc: error: " << opened.error().message << "\n";
    return open_code;
  }
  std::unique_ptr<io::Transport>& link = opened->link;

  std::vector<player::ScheduledFrame> schedule;
  schedule.reserve(frames->size());
  for (const backend::StreamFrame& f : *frames) {
    schedule.push_back({std::chrono::milliseconds(f.at_ms), f.bytes});
  }
  if (ctx.verbosity >= 0)
    ctx.err << "seqc: playing " << o.file << " on " << link->describe() << ": " << schedule.size()
            << " frames over " << compiler::format_seconds(program.duration_ms)
            << "; Ctrl-C stops the car\n";
  ctx.err.flush();

  player::PlayOptions options;
  options.interrupted = ctx.interrupted;
  options.safe_stop = backend::stop_frame();
  PlayProgress progress(ctx.err, ctx.err_is_terminal && ctx.verbosity >= 0, ctx.terminal_columns,
                        std::chrono::milliseconds(program.duration_ms), schedule.size());
  options.on_sent = [&](std::size_t i, const player::FrameTiming&) {
    progress.on_sent(i, schedule[i].at);
  };
  const player::PlayReport report = player::play(schedule, *link, ctx.clock, options);
  progress.finish();
  const player::LatenessSummary late = player::summarize(report.lateness);

  ExitCode code = ExitCode::Ok;
  const std::string stop_text = report.stop_sent ? "sent the stop (all speeds 0)"
                                                 : "could not send the stop: " + report.stop_error +
                                                       "; the car may still be moving";
  switch (report.end) {
    case player::PlayEnd::Completed:
      if (ctx.verbosity < 0) break;
      ctx.err << "seqc: played " << report.sent << " frames in "
              << compiler::format_seconds(program.duration_ms) << "; lateness p50 "
              << ms_text(late.p50) << ", p99 " << ms_text(late.p99) << ", max " << ms_text(late.max)
              << "\n";
      break;
    case player::PlayEnd::Interrupted:
      ctx.err << "seqc: interrupted after " << report.sent << " of " << schedule.size()
              << " frames; " << stop_text << "\n";
      code = ExitCode::Interrupted;
      break;
    case player::PlayEnd::WriteFailed:
      ctx.err << "seqc: error: " << report.error << " (after " << report.sent << " of "
              << schedule.size() << " frames); " << stop_text << "\n";
      code = ExitCode::DeviceFailure;
      break;
  }
  if (opened->emulator && ctx.verbosity >= 0) {
    ctx.err << "seqc: emu:raspblock received " << opened->emulator->packets().size() << " packets, "
            << opened->emulator->rejections().size() << " rejected\n";
  }
  return code;
}

}  // namespace

bool explain_no_storage(const compiler::CompileOutput& output, const std::string& path,
                        std::ostream& err) {
  if (!output.program || !std::holds_alternative<compiler::RaspblockProgram>(*output.program)) {
    return false;
  }
  err << "seqc: error: " << path
      << " is for the Raspblock board, which has no storage: it cannot keep a sequence to run "
         "later, only follow one streamed to it live\n"
         "  hint: play it with `seqc play "
      << path << " --port PORT` (e.g. --port /dev/ttyAMA0)\n";
  return true;
}

void add_play_command(CLI::App& app, Context& ctx, Outcome& result) {
  auto opts = std::make_shared<PlayOptions>();
  CLI::App* cmd = app.add_subcommand(
      "play",
      "Stream a sequence to a device live, each frame at its time (the Raspblock car board,\n"
      "or the servo controller without storing a group); Ctrl-C stops (exit 130)");
  cmd->add_option("FILE", opts->file, "Choreography file (.yaml)")->required();
  cmd->add_option("--port", opts->port,
                  "Raspblock: serial port at 115200 baud (/dev/ttyAMA0, ttyUSB0, a pty from "
                  "`seqc emulate raspblock`) or emu:raspblock. Servo controller: as for `seqc "
                  "upload` (default: the one connected; emu:xarm)");
  cmd->add_flag("--strict", opts->strict, "Treat warnings as errors");
  cmd->add_flag("--allow-late", opts->allow_late,
                "Servo controller: play a schedule the link cannot keep (moves leave late)");
  cmd->add_flag("--realtime", opts->realtime,
                "Send with real-time (SCHED_FIFO) priority, so a busy machine cannot delay frames");
  cmd->callback([&ctx, &result, opts] {
    Compiled c = compile_and_report(ctx, opts->file, opts->strict);
    result.code = c.code;
    if (!c.output.program) return;
    if (opts->realtime) {
      if (auto rt = io::request_realtime_scheduling(); !rt) {
        ctx.err << "seqc: warning: " << rt.error().message << "; playing at normal priority\n";
      }
    }
    // Each robot kind streams its own way.
    if (const auto* car = std::get_if<compiler::RaspblockProgram>(&*c.output.program)) {
      result.code = play_raspblock(*car, *opts, ctx);
    } else if (c.output.servo_program() != nullptr) {
      result.code = play_servo_program(c.output, *opts, ctx);
    }
  });
}

}  // namespace seqc::cli
