// seqc upload FILE [--port P] [--group N] [--run [--times K|--forever] [--force] [--realtime]
//                  [--music [--audio-offset MS]]] [--dry-run] [--trace FILE] [--strict]
//                  [--retries N] [--clock-ppm N] [--rig FILE] [--resync BARS]
// Compiles FILE, stores it in an action group of the board the file is for (runtime/boards)
// and, with --run, starts it. An invalid file sends nothing and opens no port. With --music the
// song of its `music:` block is decoded and the sound server reached before the port is opened;
// the group is stored without starting, then the song is played and the group started on its
// downbeat as heard (music_play.hpp); seqc stays until the song ends, and Ctrl-C stops the
// group and the song together. With --realtime the starts that keep time (on the downbeat with
// --music, at each bar line with --resync) run under SCHED_FIFO; the upload itself does not.
#include <algorithm>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>

#include <CLI/CLI.hpp>

#include "runtime/boards/board.hpp"
#include "runtime/boards/board_link.hpp"
#include "runtime/boards/dry_run.hpp"
#include "runtime/boards/resync_run.hpp"
#include "runtime/boards/upload_run.hpp"
#include "runtime/cli/board_text.hpp"
#include "runtime/cli/clock_option.hpp"
#include "runtime/cli/commands.hpp"
#include "runtime/cli/compile_report.hpp"
#include "runtime/cli/counted.hpp"
#include "runtime/cli/music_play.hpp"
#include "runtime/cli/realtime_option.hpp"
#include "runtime/cli/run_compile.hpp"
#include "runtime/cli/trace_option.hpp"
#include "runtime/io/time_text.hpp"
#include "runtime/upload/progress_text.hpp"

namespace seqc::cli {
namespace {

struct UploadArgs {
  std::string file;
  std::string port;
  int group = 0;
  bool run = false;
  int times = 1;
  bool dry_run = false;
  std::string trace;
  bool forever = false;
  bool strict = false;
  int retries = 4;
  bool force = false;     // start even if a first move is too fast from where the servos are
  bool realtime = false;  // the timed starts under SCHED_FIFO
  ClockScaleOptions clock;
  unsigned resync = 0;  // bars a piece; 0 = one group
  MusicArgs music;
};

// --times, or 0 for --forever.
std::uint16_t times_of(const UploadArgs& a) {
  return static_cast<std::uint16_t>(a.forever ? 0 : a.times);
}

// Why the upload failed, and what was done to leave the group in a known state.
void report_failure(Context& ctx, const UploadArgs& a, const upload::UploadResult& r,
                    const boards::Board& board, const compiler::CompileOutput& output) {
  if (r.status == upload::UploadStatus::OtherDialect) {
    ctx.err << "seqc: error: " << other_dialect_text(board, output) << "\nseqc: " << r.message
            << "\n";
  } else {
    ctx.err << "seqc: error: " << r.message << "\n";
  }
  ctx.err << "seqc: "
          << upload::describe_group_state(r.group_state, static_cast<std::uint8_t>(a.group))
          << "\n";
  if (r.erase_sent && r.erase_confirmed) {
    ctx.err << "seqc: sent GroupErase for group " << a.group
            << " and the controller confirmed it: step 5 was sent but never confirmed, so the "
               "group is erased rather than left holding a partial download\n";
  } else if (r.erase_sent) {
    ctx.err << "seqc: sent GroupErase for group " << a.group
            << ", but the controller did not confirm it: the group may hold a partial "
               "download; upload again\n";
  }
  if (r.stop_sent) ctx.err << "seqc: sent GroupStop: no group is playing\n";
}

// --resync: the pieces stored one group each, then started by the computer at their bar lines;
// with --music the first on the song's downbeat as heard, and the song played to its end.
ExitCode run_resync(Context& ctx, const UploadArgs& a, const compiler::CompileOutput& output,
                    const boards::Board& board, const boards::ResyncCut& cut,
                    const boards::Line& line, upload::ProgressPrinter& printer,
                    const upload::UploadOptions& options,
                    const std::optional<boards::FirstMoveTooFast>& too_fast, MusicSession* music) {
  const std::vector<compiler::ResyncPiece>& pieces = cut.pieces;
  const std::size_t last = cut.last_group;
  const auto first_group = static_cast<std::uint8_t>(a.group);
  boards::ResyncRun r =
      boards::store_pieces(board, line, output, pieces, first_group, options, &printer);
  printer.finish();
  std::optional<boards::SyncedStart> synced;
  if (r.stored()) {
    const auto realtime = realtime_stretch(ctx, a.realtime);
    synced = boards::start_pieces(board, line, pieces, first_group, options, r, music, &ctx.clock);
  }
  if (!r.stored()) {
    const upload::UploadResult& failed = r.uploads.back();
    ctx.err << "seqc: error: piece " << r.uploads.size() << " (group "
            << a.group + static_cast<int>(r.uploads.size()) - 1 << "): " << failed.message << "\n";
    return failed.status == upload::UploadStatus::BadPlan ? ExitCode::InvalidInput
                                                          : exit_code_for(failed.status);
  }
  if (r.run_refused && too_fast) {
    ctx.err << "seqc: error: " << first_move_text(*too_fast) << "; groups " << a.group << "-"
            << last << " are stored but were not started\n";
    return ExitCode::InvalidInput;
  }
  if (r.play.end == player::PlayEnd::Interrupted) {
    ctx.err << "seqc: interrupted after starting " << plural(r.play.sent, "piece") << "\n";
    return ExitCode::Interrupted;
  }
  if (r.play.end == player::PlayEnd::WriteFailed || !r.song_error.empty()) {
    return fail(ctx, r.song_error.empty() ? ExitCode::DeviceFailure : ExitCode::PortUnavailable,
                r.song_error.empty() ? r.play.error : "--music: " + r.song_error);
  }
  if (ctx.verbosity >= 0) {
    if (synced)
      ctx.err << "seqc: " << sync_text(*music, *synced, std::string(board.run_name)) << "\n";
    ctx.err << "seqc: stored " << boards::pieces_text(cut, a.resync) << " in groups " << a.group
            << "-" << last << " and started each at its bar line (the latest "
            << io::ms_text(r.latest_start(), 1) << " late)\n";
  }
  for (std::size_t k = 0; ctx.verbosity > 0 && k < pieces.size(); ++k) {
    ctx.err << "  group " << a.group + static_cast<int>(k) << ": "
            << plural(pieces[k].keyframes.size(), "action") << " from "
            << io::seconds_text(r.starts[k].at) << "\n";
  }
  if (music != nullptr && !boards::play_song_out(*music, ctx.clock, ctx.interrupted)) {
    if (board.stop_frame != nullptr) (void)line.transport.write(board.stop_frame());
    ctx.err << "seqc: interrupted: stopped the song and the piece playing\n";
    return ExitCode::Interrupted;
  }
  return ExitCode::Ok;
}

// The stored group started on the song's downbeat, then the song played to its end.
ExitCode run_to_music(Context& ctx, const UploadArgs& a, const boards::Board& board,
                      const boards::Line& line, MusicSession& music) {
  // From the song's start, whose playback clock dates the downbeat, to the group's.
  auto realtime = realtime_stretch(ctx, a.realtime);
  if (!start_music(ctx, music)) {
    ctx.err << "seqc: group " << a.group << " is stored but was not started\n";
    return ExitCode::PortUnavailable;
  }
  const boards::MusicRunReport r = boards::run_on_downbeat(
      board, line, static_cast<std::uint8_t>(a.group), times_of(a), *music.started,
      music.audio_offset, music.robot_in_emulated_time ? &ctx.clock : nullptr);
  realtime.reset();
  switch (r.play.end) {
    case player::PlayEnd::Completed:
      break;
    case player::PlayEnd::Interrupted:
      music.output->stop();
      ctx.err << "seqc: interrupted before group " << a.group
              << " started: stopped the song; group " << a.group << " is stored\n";
      return ExitCode::Interrupted;
    case player::PlayEnd::WriteFailed:
      music.output->stop();
      return fail(ctx, ExitCode::DeviceFailure, r.play.error + "; stopped the song");
  }
  if (ctx.verbosity >= 0) {
    ctx.err << "seqc: " << sync_text(music, r.start, std::string(board.run_name)) << "\n";
  }
  if (r.run && !r.run->ok()) {
    const BoardError e =
        outcome_text(*r.run, line.transport.describe(), line.timeout, board.called);
    ctx.err << "seqc: error: " << e.message << "\n";
    music.output->stop();
    return e.code;
  }
  if (ctx.verbosity >= 0) {
    ctx.err << "seqc: group " << a.group
            << (music.robot_in_emulated_time ? " started in emulated time; "
                                             : " started on the downbeat; ")
            << run_said(board, r.run) << "; playing the song to its end (Ctrl-C stops both)\n";
  }
  if (!boards::play_song_out(music, ctx.clock, ctx.interrupted)) {
    // The same stop the player sends after an early end.
    if (board.stop_frame != nullptr) (void)line.transport.write(board.stop_frame());
    ctx.err << "seqc: interrupted: stopped the song and group " << a.group << "\n";
    return ExitCode::Interrupted;
  }
  return ExitCode::Ok;
}

ExitCode run_upload(Context& ctx, const UploadArgs& a) {
  if (a.resync > 0 && (!a.run || a.dry_run)) {
    return usage_error(ctx, "--resync needs --run (the computer starts each piece), not --dry-run");
  }
  // With --run a dance longer than one group is stored as several, started by the computer
  // (compile_for_run chains), and a first move may be relative to where the robot stands.
  Compiled c = a.run && !a.dry_run
                   ? compile_for_run(ctx, a.file, a.strict, a.port, &a.clock)
                   : compile_and_report(ctx, a.file, a.strict, SongCheck::Skip, &a.clock);
  if (c.code != ExitCode::Ok) return c.code;
  if (explain_no_storage(c.output, a.file, ctx.err)) return ExitCode::InvalidInput;
  const boards::Board& board = boards::board_for(c.output);
  const auto group = static_cast<std::uint8_t>(a.group);
  std::optional<boards::ResyncCut> pieces;
  if (a.resync > 0 || boards::needs_chain(*c.output.servo_program())) {
    pieces = boards::cut_for_resync(*c.output.servo_program(), a.resync, c.clock_ppm, group);
    if (!pieces->fits()) return fail(ctx, ExitCode::InvalidInput, a.file + ": " + pieces->error);
  }
  auto planned = pieces ? boards::plan_for_piece(board, c.output, pieces->pieces.front(), group)
                        : boards::plan_for(board, c.output, group);
  if (!planned) return fail(ctx, ExitCode::InvalidInput, a.file + ": " + planned.error().message);
  const boards::Plan& plan = *planned;
  std::optional<boards::FirstMoveTooFast> too_fast;  // why may_run refused the run
  const upload::UploadOptions options = boards::upload_options(
      {group, a.retries, a.run, times_of(a), a.force, a.music.music, a.dry_run}, board, c.output,
      ctx.interrupted, too_fast);

  if (a.dry_run) {
    const boards::DryRun dry = boards::dry_run(board, plan, options);
    if (!dry.result.ok()) return fail(ctx, ExitCode::Internal, "internal: " + dry.result.message);
    ctx.out << dry.text;
    if (ctx.verbosity >= 0)
      ctx.err << "seqc: dry run: " << plural(plan.actions, "action") << " for group " << a.group
              << "; nothing was sent\n";
    return ExitCode::Ok;
  }

  MusicSession music;
  if (a.music.music) {
    MusicArgs music_args = a.music;
    music_args.rig = a.clock.rig;  // its audio_offset, unless --audio-offset is given
    if (const ExitCode e = open_music(ctx, c.output, a.file, music_args, music);
        e != ExitCode::Ok) {
      return e;
    }
  }

  stop_cleanly_from_now(ctx);
  boards::TraceFile trace;
  if (const ExitCode e = open_trace(ctx, trace, a.trace); e != ExitCode::Ok) return e;

  const boards::BoardLink link =
      boards::open_link({a.port, &board}, trace, ctx.clock, ctx.hooks, ctx.interrupted);
  if (!link.port) return say_port_failure(ctx, link, a.file);
  const boards::OpenedPort& port = *link.port;
  io::Transport* transport = link.transport;

  if (const auto i = boards::first_too_big(plan, *transport)) {
    ctx.err << "seqc: error: " << a.file << ": " << plan.frames[*i].short_what << " is a "
            << plan.frames[*i].bytes.size() << "-byte frame, and " << transport->describe()
            << " carries at most " << transport->max_frame_bytes()
            << " bytes in one report; nothing was sent (a serial port takes any frame)\n";
    return ExitCode::InvalidInput;
  }
  upload::ProgressPrinter progress(ctx.err, ctx.err_is_terminal, ctx.verbosity,
                                   ctx.terminal_columns);
  if (ctx.verbosity > 0) {
    ctx.err << "upload: " << plural(plan.actions, "action") << " into group " << a.group
            << (pieces ? " and on, " + plural(pieces->pieces.size(), "piece") : std::string())
            << " on " << transport->describe() << " (" << board.dialect->name << " dialect)\n";
  }
  const boards::Line& line = *link.line;
  music.robot_in_emulated_time = port.own_clock();
  if (pieces)
    return run_resync(ctx, a, c.output, board, *pieces, line, progress, options, too_fast,
                      a.music.music ? &music : nullptr);
  const upload::UploadResult r = boards::upload(board, line, plan, options, &progress);
  progress.finish();

  if (!r.ok()) {
    report_failure(ctx, a, r, board, c.output);
    return exit_code_for(r.status);
  }
  const double secs = std::chrono::duration<double>(r.elapsed).count();
  const std::string where = transport->describe() + (port.emulated ? ", emulated time" : "");
  std::string detail = fmt::format("{}, {:.1f} s", where, secs);
  if (r.retries > 0) detail += ", " + plural(static_cast<std::size_t>(r.retries), "re-send");
  if (r.restarts > 0) detail += ", " + plural(static_cast<std::size_t>(r.restarts), "restart");
  if (r.reopens > 0) {
    detail += ", the port came back " + plural(static_cast<std::size_t>(r.reopens), "time");
  }
  const auto not_started = [&](const boards::FirstMoveTooFast& fast) {
    return fail(ctx, ExitCode::InvalidInput,
                first_move_text(fast) + "; group " + std::to_string(a.group) +
                    " is stored but was not started");
  };
  if (r.run_refused && too_fast) return not_started(*too_fast);
  if (ctx.verbosity >= 0) {
    ctx.err << "seqc: the controller acknowledged " << plural(r.actions_acknowledged, "action")
            << " into group " << a.group << " (" << detail << ")\n";
  }
  if (a.run && a.music.music) {
    // On the downbeat the run is the computer's to send: the first-move read comes first.
    if (const auto fast = boards::run_too_fast(board, line, c.output, a.force)) {
      return not_started(*fast);
    }
    return run_to_music(ctx, a, board, line, music);
  }
  if (ctx.verbosity < 0) return ExitCode::Ok;  // --quiet: the exit status says it
  if (a.run) {
    const std::string times =
        a.forever ? "looping until stopped" : plural(static_cast<std::size_t>(a.times), "time");
    if (r.run_reported) {
      ctx.err << "seqc: group " << a.group << " started (" << times << ")\n";
    } else {
      ctx.err << "seqc: asked the controller to run group " << a.group << " (" << times << "); "
              << board.unconfirmed_run << "\n";
    }
  }
  return ExitCode::Ok;
}

}  // namespace

void add_upload_command(CLI::App& app, Context& ctx, Outcome& result) {
  auto a = std::make_shared<UploadArgs>();
  CLI::App* cmd = app.add_subcommand(
      "upload", "Compile a file and store it in an action group of the servo controller");
  cmd->add_option("FILE", a->file, "Choreography file (.yaml)")->required();
  cmd->add_option("--port", a->port,
                  "Device: /dev/ttyUSB0[@BAUD], hid, emu:xarm[?FAULTS], emu:lsc6[?OPTIONS] "
                  "(default: the one controller found)");
  cmd->add_option("--group", a->group, "Action group to store it in (0-254, default 0)")
      ->check(CLI::Range(0, 254));
  CLI::Option* run = cmd->add_flag("--run", a->run, "Start the group once it is stored");
  CLI::Option* times =
      cmd->add_option("--times", a->times, "With --run: how many times to play it (1-65535)")
          ->check(CLI::Range(1, 65535))
          ->needs(run);
  CLI::Option* forever = cmd->add_flag("--forever", a->forever, "With --run: play it until stopped")
                             ->needs(run)
                             ->excludes(times);
  cmd->add_option("--resync", a->resync,
                  "With --run: cut the dance every BARS bars into groups --group, --group + 1, "
                  "... and start each at its bar line from the computer")
      ->check(CLI::Range(1, 10000))
      ->needs(run)
      ->excludes(times)
      ->excludes(forever);
  cmd->add_flag("--force", a->force,
                "With --run: start even if a first move is too fast from where the servos are")
      ->needs(run);
  add_realtime_option(*cmd, a->realtime,
                      "With --run --music or --resync: start with real-time (SCHED_FIFO) "
                      "priority, so a busy machine cannot delay the start on the downbeat or at a "
                      "bar line (a plain --run keeps no time)",
                      run);
  add_music_options(*cmd, a->music, run, false);  // --rig is the clock options'
  cmd->add_flag("--dry-run", a->dry_run, "Print the frames it would send; open no port");
  add_trace_option(*cmd, a->trace,
                   "Write every byte sent and received, with times, to this file (docs/trace.md)");
  cmd->add_flag("--strict", a->strict, "Treat warnings as errors");
  add_clock_options(*cmd, a->clock);
  cmd->add_option("--retries", a->retries,
                  "Re-sends of one frame before giving up (0-20, default 4)")
      ->check(CLI::Range(0, 20));
  cmd->callback([&ctx, &result, a] { result.code = run_upload(ctx, *a); });
}

}  // namespace seqc::cli
