#include "runtime/cli/servo_play.hpp"

#include <algorithm>
#include <cstdio>
#include <ostream>
#include <string>
#include <vector>

#include "compiler/backend/servo_backend.hpp"
#include "compiler/source/units.hpp"
#include "runtime/cli/lsc6_commands.hpp"
#include "runtime/cli/play_progress.hpp"
#include "runtime/cli/port_open.hpp"
#include "runtime/player/player.hpp"
#include "runtime/protocol/lsc6_messages.hpp"

namespace seqc::cli {
namespace {

// How often Ctrl-C is looked at while the last move finishes.
constexpr io::Duration kPollInterval = std::chrono::milliseconds(20);

std::string where(const compiler::CompileOutput& compiled, const compiler::Keyframe& k) {
  if (k.source.file == compiler::kNoFile || k.source.file >= compiled.sources.file_count()) {
    return "";
  }
  return " (" + compiled.sources.path(k.source.file) + ":" + std::to_string(k.source.line) + ")";
}

std::string ms_text(io::Duration d) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f ms", std::chrono::duration<double, std::milli>(d).count());
  return buf;
}

// One frame per keyframe, in the program's dialect.
Result<std::vector<player::ScheduledFrame>> live_frames(const compiler::ServoProgram& program) {
  std::vector<player::ScheduledFrame> frames;
  if (backend::uses_lsc6_dialect(program)) {
    for (const compiler::Keyframe& k : program.keyframes) {
      lsc6::Move move{k.time_ms, {}};
      for (const lsc::ServoTarget& t : k.targets) move.servos.push_back({t.id, t.position});
      auto bytes = lsc6::encode_serial(lsc6::Request{move});
      if (!bytes) return bytes.error();
      frames.push_back({std::chrono::milliseconds(k.start_ms), std::move(*bytes)});
    }
    return frames;
  }
  for (const backend::TimedMove& m : backend::live_moves(program)) {
    auto bytes = lsc::encode_serial(m.move);
    if (!bytes) return bytes.error();
    frames.push_back({std::chrono::milliseconds(m.send_ms), std::move(*bytes)});
  }
  return frames;
}

std::string link_text(const io::Transport& t) {
  if (t.seconds_per_byte() > 0) {
    return "at " + std::to_string(static_cast<long>(10.0 / t.seconds_per_byte() + 0.5)) + " baud";
  }
  return "at one report per " + ms_text(t.frame_interval());
}

// False when a move cannot go over the link at all, or the link cannot keep the schedule and
// late moves are not allowed (said why).
bool schedule_fits(Context& ctx, const compiler::CompileOutput& compiled,
                   const std::vector<player::ScheduledFrame>& frames, const io::Transport& t,
                   const LivePlayOptions& o) {
  if (const std::size_t limit = t.max_frame_bytes(); limit > 0) {
    for (std::size_t i = 0; i < frames.size(); ++i) {
      if (frames[i].bytes.size() > limit) {
        ctx.err << "seqc: error: move " << i + 1 << " is a " << frames[i].bytes.size()
                << "-byte frame, and " << t.describe() << " carries at most " << limit
                << " bytes in one report; nothing was sent\n";
        return false;
      }
    }
  }
  const player::ScheduleCheck c =
      player::check_schedule(frames, t.seconds_per_byte(), t.frame_interval());
  if (!c.first_late) return true;
  const compiler::ServoProgram& program = *compiled.servo_program();
  const std::size_t i = *c.first_late;
  const compiler::Keyframe& k = program.keyframes[i];
  const std::string what =
      "move " + std::to_string(i + 1) + " of " + std::to_string(frames.size()) + " at " +
      compiler::format_seconds(k.start_ms) + where(compiled, k) + " would leave " +
      ms_text(c.late_by) + " late: " + link_text(t) + " the move before it takes " +
      ms_text(c.wire_time) + " on the wire (" + std::to_string(c.late_frames) + " of " +
      std::to_string(frames.size()) + " moves late, the worst by " + ms_text(c.worst) + ")";
  const std::string fix = "store it on the controller and run it there: seqc upload " +
                          (o.file.empty() ? std::string("FILE") : o.file) + " --run";
  if (o.allow_late) {
    ctx.err << "seqc: warning: " << t.describe() << " cannot keep this schedule: " << what
            << "; playing it late (--allow-late)\n  hint: " << fix << "\n";
    return true;
  }
  ctx.err << "seqc: error: " << t.describe() << " cannot keep this schedule: " << what << "\n"
          << "  hint: " << fix << "\n"
          << "  hint: or play it late anyway with --allow-late\n";
  return false;
}

// Streams `frames` and waits for the last move to end; says how it went.
ExitCode stream(Context& ctx, const compiler::CompileOutput& compiled,
                const std::vector<player::ScheduledFrame>& frames, io::Transport& transport,
                io::Clock& clock) {
  const compiler::ServoProgram& program = *compiled.servo_program();
  if (ctx.verbosity >= 0) {
    ctx.err << "seqc: playing " << frames.size() << " moves ("
            << compiler::format_seconds(program.duration_ms()) << ") live on "
            << transport.describe() << "; Ctrl-C stops\n";
  }
  player::PlayOptions options;
  options.interrupted = ctx.interrupted;
  options.drain = true;
  options.seconds_per_byte = transport.seconds_per_byte();
  PlayProgress progress(ctx.err, ctx.err_is_terminal && ctx.verbosity >= 0, ctx.terminal_columns,
                        std::chrono::milliseconds(program.duration_ms()), frames.size());
  options.on_sent = [&](std::size_t i, const player::FrameTiming&) {
    progress.on_sent(i, frames[i].at);
  };
  const player::PlayReport report = player::play(frames, transport, clock, options);
  progress.finish();
  const std::size_t sent = report.sent;
  const auto last_step = [&] {
    if (sent == 0) return std::string("before the first step");
    const compiler::Keyframe& k = program.keyframes[sent - 1];
    return "after step " + std::to_string(sent) + " of " + std::to_string(frames.size()) + " at " +
           compiler::format_seconds(k.start_ms) + where(compiled, k);
  };
  switch (report.end) {
    case player::PlayEnd::Completed: {
      // The last move is still running: return when the sequence ends, so "played" means the
      // robot is in its final pose (and the next command sees it there).
      const io::TimePoint end = report.started + std::chrono::milliseconds(program.duration_ms());
      while (clock.now() < end) {
        if (ctx.interrupted != nullptr && ctx.interrupted->load()) {
          ctx.err << "seqc: interrupted during the last move: every step was sent\n";
          return ExitCode::Interrupted;
        }
        clock.sleep_until(std::min(end, clock.now() + kPollInterval));
      }
      if (ctx.verbosity < 0) return ExitCode::Ok;
      const player::LatenessSummary late = player::summarize(report.left_lateness);
      ctx.err << "seqc: played " << sent << " moves, "
              << compiler::format_seconds(program.duration_ms())
              << "; moves left the port late by p50 " << ms_text(late.p50) << ", p99 "
              << ms_text(late.p99) << ", max " << ms_text(late.max)
              << " (measured once each had left)\n";
      return ExitCode::Ok;
    }
    case player::PlayEnd::Interrupted:
      ctx.err << "seqc: interrupted: stopped sending " << last_step()
              << "; the servos finish the move they were given\n";
      return ExitCode::Interrupted;
    case player::PlayEnd::WriteFailed:
      ctx.err << "seqc: error: sending to " << transport.describe() << " failed " << last_step()
              << ": " << report.error << "\n";
      return ExitCode::DeviceFailure;
  }
  return ExitCode::Internal;
}

}  // namespace

ExitCode stream_servo_program(Context& ctx, const compiler::CompileOutput& compiled,
                              ControllerSession& s, const LivePlayOptions& o) {
  const compiler::ServoProgram* program = compiled.servo_program();
  if (program == nullptr) {
    ctx.err << "seqc: error: internal: play_on_servo_controller without a servo program\n";
    return ExitCode::Internal;
  }
  auto frames = live_frames(*program);
  if (!frames) {
    ctx.err << "seqc: error: internal: " << frames.error().message << "\n";
    return ExitCode::Internal;
  }
  if (!schedule_fits(ctx, compiled, *frames, s.link().transport(), o)) {
    return ExitCode::InvalidInput;
  }
  if (!s.ask<lsc::BatteryVoltage>(lsc::GetBatteryVoltage{}, "the battery voltage")) {
    return ExitCode::DeviceFailure;
  }
  return stream(ctx, compiled, *frames, s.link().transport(), s.link().clock());
}

ExitCode play_on_servo_controller(Context& ctx, const compiler::CompileOutput& compiled,
                                  const DeviceOptions& device, const LivePlayOptions& o) {
  const compiler::ServoProgram* program = compiled.servo_program();
  if (program == nullptr || !backend::uses_lsc6_dialect(*program)) {
    return run_on_controller(ctx, device, [&](ControllerSession& s) {
      return stream_servo_program(ctx, compiled, s, o);
    });
  }
  // The LSC-6: no command answers, so nothing can show the board is there before playing.
  auto frames = live_frames(*program);
  if (!frames) {
    ctx.err << "seqc: error: " << frames.error().message << "\n";
    return ExitCode::InvalidInput;
  }
  PortOpenResult opened = open_controller_port(device.port, ctx);
  if (!opened.port) {
    ctx.err << "seqc: error: " << opened.failure.message << "\n";
    return opened.failure.code;
  }
  io::Transport& transport = *opened.port->transport;
  if (!schedule_fits(ctx, compiled, *frames, transport, o)) return ExitCode::InvalidInput;
  if (ctx.verbosity >= 0) {
    ctx.err << "seqc: note: the LSC-6 answers no move, so nothing shows that the board hears "
               "them\n";
  }
  return stream(ctx, compiled, *frames, transport, *opened.port->clock);
}

}  // namespace seqc::cli
