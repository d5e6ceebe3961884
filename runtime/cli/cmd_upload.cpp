// seqc upload FILE [--port P] [--group N] [--run [--times K|--forever] [--music
//                  [--audio-offset MS]]] [--dry-run] [--trace FILE] [--strict] [--retries N]
// Compiles FILE, stores it in an action group of the board the file is for (runtime/boards)
// and, with --run, starts it. An invalid file sends nothing and opens no port. With --music the
// song of its `music:` block is decoded and the sound server reached before the port is opened;
// the group is stored without starting, then the song is played and the group started on its
// downbeat as heard (music_play.hpp); seqc stays until the song ends, and Ctrl-C stops the
// group and the song together.
#include <fstream>
#include <memory>
#include <string>

#include <fmt/format.h>

#include "runtime/boards/board.hpp"
#include "runtime/boards/dry_run.hpp"
#include "runtime/boards/ports.hpp"
#include "runtime/cli/board_text.hpp"
#include "runtime/cli/commands.hpp"
#include "runtime/cli/compile_report.hpp"
#include "runtime/cli/music_play.hpp"
#include "runtime/upload/progress_text.hpp"
#include "runtime/upload/trace_transport.hpp"

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
  MusicArgs music;
};

std::string plural(std::size_t n, const char* word) {
  return fmt::format("{} {}{}", n, word, n == 1 ? "" : "s");
}

// Why the upload failed, and what was done to leave the group in a known state.
void report_failure(Context& ctx, const UploadArgs& a, const upload::UploadResult& r,
                    const boards::Board& board, const compiler::CompileOutput& output) {
  if (r.status == upload::UploadStatus::OtherDialect) {
    const compiler::ServoProgram* program = output.servo_program();
    ctx.err << "seqc: error: "
            << other_dialect_text(board, program != nullptr ? program->robot.profile : "")
            << "\nseqc: " << r.message << "\n";
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

// The stored group started on the song's downbeat, then the song played to its end.
ExitCode run_to_music(Context& ctx, const UploadArgs& a, const boards::Board& board,
                      const boards::Line& line, MusicSession& music) {
  if (!start_music(ctx, music)) {
    ctx.err << "seqc: group " << a.group << " is stored but was not started\n";
    return ExitCode::PortUnavailable;
  }
  const auto times = static_cast<std::uint16_t>(a.forever ? 0 : a.times);
  const boards::MusicRunReport r = boards::run_on_downbeat(
      board, line, static_cast<std::uint8_t>(a.group), times, *music.started, music.audio_offset);
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
      ctx.err << "seqc: error: " << r.play.error << "; stopped the song\n";
      return ExitCode::DeviceFailure;
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
    const std::string said = r.run && r.run->started == boards::Confirmation::Reported
                                 ? std::string(board.called) + " reported it started"
                                 : std::string(board.unconfirmed_run);
    ctx.err << "seqc: group " << a.group << " started on the downbeat; " << said
            << "; playing the song to its end (Ctrl-C stops both)\n";
  }
  if (!play_song_out(ctx, music, ctx.clock)) {
    // The same stop the player sends after an early end.
    if (board.stop_frame != nullptr) (void)line.transport.write(board.stop_frame());
    ctx.err << "seqc: interrupted: stopped the song and group " << a.group << "\n";
    return ExitCode::Interrupted;
  }
  return ExitCode::Ok;
}

ExitCode run_upload(Context& ctx, const UploadArgs& a) {
  Compiled c = compile_and_report(ctx, a.file, a.strict);
  if (c.code != ExitCode::Ok) return c.code;
  if (explain_no_storage(c.output, a.file, ctx.err)) return ExitCode::InvalidInput;
  const boards::Board& board = boards::board_for(c.output);
  const auto group = static_cast<std::uint8_t>(a.group);
  auto planned = boards::plan_for(board, c.output, group);
  if (!planned) {
    ctx.err << "seqc: error: " << a.file << ": " << planned.error().message << "\n";
    return ExitCode::InvalidInput;
  }
  const boards::Plan& plan = *planned;
  upload::UploadOptions options;
  options.group = group;
  options.retries = a.retries;
  // With --music the run is sent on the downbeat, after the upload (a dry run still shows it).
  options.run = a.run && (!a.music.music || a.dry_run);
  options.run_times = static_cast<std::uint16_t>(a.forever ? 0 : a.times);

  if (a.dry_run) {
    const boards::DryRun dry = boards::dry_run(board, plan, options);
    if (!dry.result.ok()) {
      ctx.err << "seqc: error: internal: " << dry.result.message << "\n";
      return ExitCode::Internal;
    }
    ctx.out << dry.text;
    if (ctx.verbosity >= 0)
      ctx.err << "seqc: dry run: " << plural(plan.actions, "action") << " for group " << a.group
              << "; nothing was sent\n";
    return ExitCode::Ok;
  }

  MusicSession music;
  if (a.music.music) {
    if (const ExitCode e = open_music(ctx, c.output, a.file, a.music, music); e != ExitCode::Ok) {
      return e;
    }
  }

  std::ofstream trace_file;
  if (!a.trace.empty()) {
    trace_file.open(a.trace, std::ios::out | std::ios::trunc);
    if (!trace_file) {
      ctx.err << "seqc: error: --trace " << a.trace << ": cannot write the file\n";
      return ExitCode::FileError;
    }
  }

  const boards::PortRequest request{a.port, &board};
  boards::OpenResult opened = boards::open_port(request, ctx.clock, ctx.hooks);
  if (!opened.port) {
    const BoardError e = port_failure(opened.failure, request, a.file);
    ctx.err << "seqc: error: " << e.message << "\n";
    return e.code;
  }
  boards::OpenedPort& port = *opened.port;
  io::Clock& clock = *port.clock;
  std::unique_ptr<upload::TraceTransport> trace;
  io::Transport* transport = port.transport.get();
  if (trace_file.is_open()) {
    trace = std::make_unique<upload::TraceTransport>(*transport, clock, trace_file, board.name);
    transport = trace.get();
  }

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
    ctx.err << "upload: " << plural(plan.actions, "action") << " into group " << a.group << " on "
            << transport->describe() << " (" << board.name << " dialect)\n";
  }
  const boards::Line line{*transport, clock, ctx.interrupted};
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
  if (ctx.verbosity >= 0) {
    ctx.err << "seqc: the controller acknowledged " << plural(r.actions_acknowledged, "action")
            << " into group " << a.group << " (" << detail << ")\n";
  }
  if (a.run && a.music.music) return run_to_music(ctx, a, board, line, music);
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
  cmd->add_flag("--forever", a->forever, "With --run: play it until stopped")
      ->needs(run)
      ->excludes(times);
  add_music_options(*cmd, a->music, run);
  cmd->add_flag("--dry-run", a->dry_run, "Print the frames it would send; open no port");
  cmd->add_option("--trace", a->trace,
                  "Write every byte sent and received, with times, to this file (docs/trace.md)");
  cmd->add_flag("--strict", a->strict, "Treat warnings as errors");
  cmd->add_option("--retries", a->retries,
                  "Re-sends of one frame before giving up (0-20, default 4)")
      ->check(CLI::Range(0, 20));
  cmd->callback([&ctx, &result, a] { result.code = run_upload(ctx, *a); });
}

}  // namespace seqc::cli
