#include "runtime/cli/servo_play.hpp"

#include "runtime/cli/play_progress.hpp"

#include <algorithm>
#include <ostream>
#include <string>
#include <vector>

#include "compiler/backend/servo_backend.hpp"
#include "compiler/source/units.hpp"
#include "runtime/player/player.hpp"

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

}  // namespace

ExitCode stream_servo_program(Context& ctx, const compiler::CompileOutput& compiled,
                              ControllerSession& s) {
  const compiler::ServoProgram* program = compiled.servo_program();
  if (program == nullptr) {
    ctx.err << "seqc: error: internal: play_on_servo_controller without a servo program\n";
    return ExitCode::Internal;
  }
  const std::vector<backend::TimedMove> moves = backend::live_moves(*program);
  std::vector<player::ScheduledFrame> frames;
  frames.reserve(moves.size());
  for (const backend::TimedMove& m : moves) {
    auto bytes = lsc::encode_serial(m.move);
    if (!bytes) {
      ctx.err << "seqc: error: internal: " << bytes.error().message << "\n";
      return ExitCode::Internal;
    }
    frames.push_back({std::chrono::milliseconds(m.send_ms), std::move(*bytes)});
  }

  {
    if (!s.ask<lsc::BatteryVoltage>(lsc::GetBatteryVoltage{}, "the battery voltage")) {
      return ExitCode::DeviceFailure;
    }
    if (ctx.verbosity >= 0)
      ctx.err << "seqc: playing " << frames.size() << " moves ("
              << compiler::format_seconds(program->duration_ms()) << ") live on " << s.port_name()
              << "; Ctrl-C stops\n";
    player::PlayOptions options;
    options.interrupted = ctx.interrupted;
    PlayProgress progress(ctx.err, ctx.err_is_terminal && ctx.verbosity >= 0, ctx.terminal_columns,
                          std::chrono::milliseconds(program->duration_ms()), frames.size());
    options.on_sent = [&](std::size_t i, const player::FrameTiming&) {
      progress.on_sent(i, frames[i].at);
    };
    const player::PlayReport report =
        player::play(frames, s.link().transport(), s.link().clock(), options);
    progress.finish();
    const std::size_t sent = report.sent;
    const auto last_step = [&] {
      if (sent == 0) return std::string("before the first step");
      const compiler::Keyframe& k = program->keyframes[sent - 1];
      return "after step " + std::to_string(sent) + " of " + std::to_string(frames.size()) +
             " at " + compiler::format_seconds(k.start_ms) + where(compiled, k);
    };
    switch (report.end) {
      case player::PlayEnd::Completed: {
        // The last move is still running: return when the sequence ends, so "played" means
        // the robot is in its final pose (and the next command sees it there).
        io::Clock& clock = s.link().clock();
        const io::TimePoint end =
            report.started + std::chrono::milliseconds(program->duration_ms());
        while (clock.now() < end) {
          if (ctx.interrupted != nullptr && ctx.interrupted->load()) {
            ctx.err << "seqc: interrupted during the last move: every step was sent\n";
            return ExitCode::Interrupted;
          }
          clock.sleep_until(std::min(end, clock.now() + kPollInterval));
        }
        const player::LatenessSummary late = player::summarize(report.lateness);
        const auto us = [](io::Duration d) {
          return std::to_string(std::chrono::duration_cast<std::chrono::microseconds>(d).count());
        };
        if (ctx.verbosity < 0) return ExitCode::Ok;
        ctx.err << "seqc: played " << sent << " moves, "
                << compiler::format_seconds(program->duration_ms()) << " (send lateness p50 "
                << us(late.p50) << " us, p99 " << us(late.p99) << " us, max " << us(late.max)
                << " us)\n";
        return ExitCode::Ok;
      }
      case player::PlayEnd::Interrupted:
        ctx.err << "seqc: interrupted: stopped sending " << last_step()
                << "; the servos finish the move they were given\n";
        return ExitCode::Interrupted;
      case player::PlayEnd::WriteFailed:
        ctx.err << "seqc: error: sending to " << s.port_name() << " failed " << last_step() << ": "
                << report.error << "\n";
        return ExitCode::DeviceFailure;
    }
    return ExitCode::Internal;
  }
}

ExitCode play_on_servo_controller(Context& ctx, const compiler::CompileOutput& compiled,
                                  const DeviceOptions& device) {
  return run_on_controller(
      ctx, device, [&](ControllerSession& s) { return stream_servo_program(ctx, compiled, s); });
}

}  // namespace seqc::cli
