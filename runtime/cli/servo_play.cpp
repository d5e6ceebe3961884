#include "runtime/cli/servo_play.hpp"

#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "base/units.hpp"
#include "runtime/boards/board_link.hpp"
#include "runtime/boards/first_move.hpp"
#include "runtime/boards/live.hpp"
#include "runtime/cli/board_text.hpp"
#include "runtime/cli/device_command.hpp"
#include "runtime/cli/play_progress.hpp"
#include "runtime/cli/trace_option.hpp"
#include "runtime/io/time_text.hpp"

namespace seqc::cli {
namespace {

// " (walk.yaml:7)": where the source writes the step a move comes from.
std::string where(const compiler::CompileOutput& compiled, const boards::LiveReport& r,
                  std::size_t move) {
  if (move >= r.origins.size()) return "";
  const seqc::Location& at = r.origins[move].source;
  if (at.file == seqc::kNoFile || at.file >= compiled.sources.file_count()) return "";
  return " (" + compiled.sources.path(at.file) + ":" + std::to_string(at.line) + ")";
}

// "0.5 s": when the step a move comes from starts.
std::string start_of(const boards::LiveReport& r, std::size_t move) {
  return move < r.origins.size() ? seqc::format_seconds(r.origins[move].start_ms) : "?";
}

// The first late move of a schedule the link cannot keep, and by how much.
std::string late_text(const compiler::CompileOutput& compiled, const boards::LiveReport& r,
                      const io::Transport& t) {
  const player::ScheduleCheck& c = r.check;
  const std::size_t i = *c.first_late;
  const std::string n = std::to_string(r.frames.size());
  return "move " + std::to_string(i + 1) + " of " + n + " at " + start_of(r, i) +
         where(compiled, r, i) + " would leave " + io::ms_text(c.late_by, 1) +
         " late: " + io::pace_text(t.seconds_per_byte(), t.frame_interval()) +
         " the move before it takes " + io::ms_text(c.wire_time, 1) + " on the wire (" +
         std::to_string(c.late_frames) + " of " + n + " moves late, the worst by " +
         io::ms_text(c.worst, 1) + ")";
}

// A servo board's report: moves, measured once each had left.
ExitCode word_moves(Context& ctx, const compiler::CompileOutput& compiled,
                    const boards::LiveReport& r, const boards::Line& line, const PlayArgs& args,
                    const boards::Board& board) {
  const io::Transport& t = line.transport;
  const std::string fix = "store it on the controller and run it there: seqc upload " +
                          (args.file.empty() ? std::string("FILE") : args.file) + " --run";
  const std::size_t sent = r.play.sent;
  const auto last_step = [&] {
    if (sent == 0) return std::string("before the first step");
    return "after step " + std::to_string(sent) + " of " + std::to_string(r.frames.size()) +
           " at " + start_of(r, sent - 1) + where(compiled, r, sent - 1);
  };
  switch (r.status) {
    case boards::LiveStatus::BadProgram:
      ctx.err << "seqc: error: internal: " << r.error << "\n";
      return ExitCode::Internal;
    case boards::LiveStatus::NotStarted:  // the start hook said why
      return ExitCode::PortUnavailable;
    case boards::LiveStatus::FrameTooBig:
      ctx.err << "seqc: error: move " << *r.too_big + 1 << " is a "
              << r.frames[*r.too_big].bytes.size() << "-byte frame, and " << t.describe()
              << " carries at most " << t.max_frame_bytes() << " bytes in one report; nothing "
              << "was sent\n";
      return ExitCode::InvalidInput;
    case boards::LiveStatus::LateSchedule:
      ctx.err << "seqc: error: " << t.describe()
              << " cannot keep this schedule: " << late_text(compiled, r, t) << "\n"
              << "  hint: " << fix << "\n"
              << "  hint: or play it late anyway with --allow-late\n";
      return ExitCode::InvalidInput;
    case boards::LiveStatus::NoBoard:
      if (r.probe.failure == boards::Failure::OtherDialect) {
        ctx.err << "seqc: error: " << other_dialect_text(board, compiled)
                << "\nseqc: no move was sent\n";
        return ExitCode::Usage;
      }
      return report_outcome(ctx, r.probe, line, t.describe(), board);
    case boards::LiveStatus::Played: {
      if (ctx.verbosity < 0) return ExitCode::Ok;
      const player::LatenessSummary late = player::summarize(r.play.left_lateness);
      ctx.err << "seqc: played " << sent << " moves, " << seqc::format_seconds(r.length_ms)
              << "; moves left the port late by p50 " << io::ms_text(late.p50, 1) << ", p99 "
              << io::ms_text(late.p99, 1) << ", max " << io::ms_text(late.max, 1)
              << " (measured once each had left)\n";
      return ExitCode::Ok;
    }
    case boards::LiveStatus::InterruptedAtEnd:
      ctx.err << "seqc: interrupted during the last move: every step was sent\n";
      return ExitCode::Interrupted;
    case boards::LiveStatus::Interrupted:
      ctx.err << "seqc: interrupted: stopped sending " << last_step()
              << "; the servos finish the move they were given\n";
      return ExitCode::Interrupted;
    case boards::LiveStatus::WriteFailed:
      ctx.err << "seqc: error: sending to " << t.describe() << " failed " << last_step() << ": "
              << r.play.error << "\n";
      return ExitCode::DeviceFailure;
  }
  return ExitCode::Internal;
}

// A car's report: frames, their lateness, and the stop after an early end.
ExitCode word_stream(Context& ctx, const boards::LiveReport& r) {
  const player::PlayReport& p = r.play;
  const std::string stop_text =
      p.stop_sent ? "sent the stop (all speeds 0)"
                  : "could not send the stop: " + p.stop_error + "; the car may still be moving";
  switch (r.status) {
    case boards::LiveStatus::Played:
    case boards::LiveStatus::InterruptedAtEnd: {
      if (ctx.verbosity < 0) return ExitCode::Ok;
      const player::LatenessSummary late = player::summarize(p.lateness);
      ctx.err << "seqc: played " << p.sent << " frames in " << seqc::format_seconds(r.length_ms)
              << "; lateness p50 " << io::ms_text(late.p50, 2) << ", p99 "
              << io::ms_text(late.p99, 2) << ", max " << io::ms_text(late.max, 2) << "\n";
      return ExitCode::Ok;
    }
    case boards::LiveStatus::Interrupted:
      ctx.err << "seqc: interrupted after " << p.sent << " of " << r.frames.size() << " frames; "
              << stop_text << "\n";
      return ExitCode::Interrupted;
    case boards::LiveStatus::WriteFailed:
      ctx.err << "seqc: error: " << p.error << " (after " << p.sent << " of " << r.frames.size()
              << " frames); " << stop_text << "\n";
      return ExitCode::DeviceFailure;
    default:
      ctx.err << "seqc: error: " << r.error << "\n";
      return ExitCode::Internal;
  }
}

// Plays and words it; the lines that belong before the first frame are said from the hooks.
ExitCode play_and_word(Context& ctx, const compiler::CompileOutput& compiled,
                       const boards::Board& board, const boards::Line& line, const PlayArgs& args,
                       MusicSession* music = nullptr) {
  const io::Transport& t = line.transport;
  const bool moves = board.style == boards::LiveStyle::Moves;
  std::optional<PlayProgress> progress;
  boards::LiveHooks hooks;
  hooks.checked = [&](const boards::LiveReport& r) {
    if (!r.check.first_late) return;
    ctx.err << "seqc: warning: " << t.describe()
            << " cannot keep this schedule: " << late_text(compiled, r, t)
            << "; playing it late (--allow-late)\n  hint: store it on the controller and run it "
               "there: seqc upload "
            << (args.file.empty() ? std::string("FILE") : args.file) << " --run\n";
  };
  hooks.starting = [&](const boards::LiveReport& r) {
    if (ctx.verbosity >= 0 && !board.unprobed_note.empty()) {
      ctx.err << "seqc: note: " << board.unprobed_note << "\n";
    }
    const std::string length = seqc::format_seconds(r.length_ms);
    if (ctx.verbosity >= 0 && moves) {
      ctx.err << "seqc: playing " << r.frames.size() << " moves (" << length << ") live on "
              << t.describe() << "; Ctrl-C stops\n";
    } else if (ctx.verbosity >= 0) {
      ctx.err << "seqc: playing " << args.file << " on " << t.describe() << ": " << r.frames.size()
              << " frames over " << length << "; Ctrl-C stops the car\n";
    }
    ctx.err.flush();
    progress.emplace(ctx.err, ctx.err_is_terminal && ctx.verbosity >= 0, ctx.terminal_columns,
                     std::chrono::milliseconds(r.length_ms), r.frames.size());
  };
  hooks.sent = [&](std::size_t i, io::Duration at) { progress->on_sent(i, at); };
  std::optional<boards::LiveSongStart> planned;
  if (music != nullptr) {
    hooks.start = [&](const boards::LiveReport& r) -> std::optional<boards::LiveStart> {
      if (!start_music(ctx, *music)) return std::nullopt;
      const std::size_t bytes = r.frames.empty() ? 0 : r.frames[0].bytes.size();
      planned = boards::live_song_start(board, *music, bytes, line.transport.seconds_per_byte(),
                                        ctx.clock, line.clock);
      return planned->start;
    };
  }
  const boards::LiveReport r = boards::play_live(board, compiled, line, args.allow_late, hooks);
  if (progress) progress->finish();
  if (r.status == boards::LiveStatus::NotStarted) return ExitCode::PortUnavailable;
  if (music != nullptr && planned && ctx.verbosity >= 0) {
    const boards::SyncedStart start = boards::synced_start(
        planned->plan, planned->wire, board.start_delay, boards::first_written(r.play));
    ctx.err << "seqc: " << sync_text(*music, start, moves ? "the first move" : "the first frame")
            << "\n";
  }
  const ExitCode code =
      moves ? word_moves(ctx, compiled, r, line, args, board) : word_stream(ctx, r);
  if (music == nullptr || !music->output) return code;
  if (code != ExitCode::Ok) {
    music->output->stop();
    return code;
  }
  if (ctx.verbosity >= 0) ctx.err << "seqc: playing the song to its end (Ctrl-C stops it)\n";
  if (!boards::play_song_out(*music, ctx.clock, ctx.interrupted)) {
    ctx.err << "seqc: interrupted: stopped the song\n";
    return ExitCode::Interrupted;
  }
  return ExitCode::Ok;
}

}  // namespace

ExitCode play_on_board(Context& ctx, const compiler::CompileOutput& compiled,
                       const PlayArgs& args) {
  const boards::Board& board = boards::board_for(compiled);
  stop_cleanly_from_now(ctx);
  boards::TraceFile trace;
  if (const ExitCode c = open_trace(ctx, trace, args.trace); c != ExitCode::Ok) return c;
  MusicSession music;
  if (args.music.music) {
    if (const ExitCode e = open_music(ctx, compiled, args.file, args.music, music);
        e != ExitCode::Ok) {
      return e;
    }
  }
  const boards::BoardLink link =
      boards::open_link({args.port, &board}, trace, ctx.clock, ctx.hooks, ctx.interrupted);
  if (!link.port) return say_port_failure(ctx, link, args.file);
  const boards::OpenedPort& port = *link.port;
  const boards::Line& line = *link.line;
  if (const auto fast = boards::run_too_fast(board, line, compiled, args.force)) {
    ctx.err << "seqc: error: " << first_move_text(*fast) << "\n";
    return ExitCode::InvalidInput;
  }
  music.robot_in_emulated_time = port.own_clock();
  const ExitCode code =
      play_and_word(ctx, compiled, board, line, args, args.music.music ? &music : nullptr);
  if (const auto got = boards::received(port); got && ctx.verbosity >= 0) {
    ctx.err << "seqc: " << port.transport->describe() << " received " << got->packets
            << " packets, " << got->rejected << " rejected\n";
  }
  return code;
}

ExitCode play_on_line(Context& ctx, const compiler::CompileOutput& compiled,
                      const boards::Line& line, const PlayArgs& args) {
  return play_and_word(ctx, compiled, boards::board_for(compiled), line, args);
}

}  // namespace seqc::cli
