// seqc show SHOW.yaml: several performers on one clock (compiler/show.hpp). Every file is
// checked first; then each stored performer's group is uploaded (progress per performer), and
// nothing starts unless every upload completed and, where a board reports its servos, every
// performer's first move is safe from where they are (boards/first_move.hpp; --force skips the
// read). Then everything starts at one instant
// (boards::perform): one player, one track per performer, a stored performer's run command at
// t = 0 and a streamed performer's frames at their times, so "one instant" is one deadline, not
// several programs' guesses; each is written early by its first frame's wire time, so it
// finishes arriving then (boards/show.hpp). The report gives each performer's start (how long
// after the common deadline its first frame finished arriving, plus its board's start delay)
// and, for a stored one, whether the board said it started; the skew between performers; and
// the lateness of streamed frames. With --music the performers' song (every performer with a
// `music:` block must name the same song and downbeat) plays, and the common deadline is its
// downbeat as heard (music_play.hpp). With --realtime the start and the performance (from the
// song's start with --music) run under SCHED_FIFO; the uploads before do not.
#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "base/terminal_text.hpp"
#include "compiler/show.hpp"
#include "runtime/boards/board.hpp"
#include "runtime/boards/first_move.hpp"
#include "runtime/boards/ports.hpp"
#include "runtime/boards/show.hpp"
#include "runtime/cli/board_text.hpp"
#include "runtime/cli/commands.hpp"
#include "runtime/cli/compile_report.hpp"
#include "runtime/cli/counted.hpp"
#include "runtime/cli/music_play.hpp"
#include "runtime/cli/realtime_option.hpp"
#include "runtime/cli/trace_option.hpp"
#include "runtime/io/time_text.hpp"
#include "runtime/upload/progress_text.hpp"

namespace seqc::cli {
namespace {

// How long a stored performer's board is given to confirm its start.
constexpr io::Duration kReplyTimeout = std::chrono::seconds(1);

using Stage = boards::ShowStage;

ExitCode open_stage(Context& ctx, const compiler::Performer& p, Stage& stage,
                    const std::string& trace_prefix) {
  const boards::StageOpen o = boards::open_stage(p, trace_prefix, ctx.clock, ctx.hooks, stage);
  switch (o.problem) {
    case boards::StageProblem::None:
      return ExitCode::Ok;
    case boards::StageProblem::NoPort:
      return usage_error(ctx,
                         "performer '" + terminal_safe(p.name) + "' has no port in the show file");
    case boards::StageProblem::TraceUnwritable:
      return trace_unwritable(ctx, o.trace_path);
    case boards::StageProblem::PortFailed:
      break;
  }
  const BoardError e = port_failure(o.failure, o.request, p.file);
  return fail(ctx, e.code, terminal_safe(p.name) + ": " + e.message);
}

// Stores a performer's group: Ok, or (with the reason said) Interrupted when a stop signal ended
// it, as for `seqc upload`, else DeviceFailure.
ExitCode upload_stage(Context& ctx, Stage& stage) {
  const compiler::Performer& p = *stage.performer;
  auto planned = boards::stage_plan(stage);
  if (!planned) {
    return fail(ctx, ExitCode::DeviceFailure,
                terminal_safe(p.name) + ": " + planned.error().message);
  }
  if (ctx.verbosity >= 0) {
    ctx.err << "seqc: " << terminal_safe(p.name) << ": uploading "
            << plural(planned->actions, "action") << " into group " << p.group << " on "
            << stage.port->transport->describe() << "\n";
  }
  upload::ProgressPrinter progress(ctx.err, ctx.err_is_terminal, ctx.verbosity,
                                   ctx.terminal_columns);
  const upload::UploadResult r = boards::upload_stage(stage, *planned, ctx.interrupted, &progress);
  progress.finish();
  if (r.status == upload::UploadStatus::OtherDialect) {
    ctx.err << "seqc: error: " << terminal_safe(p.name) << ": "
            << other_dialect_text(*stage.board, p.output) << "\nseqc: " << terminal_safe(p.name)
            << ": " << r.message << "\n";
    return exit_code_for(r.status);  // the wrong board for the file: 2, as `upload` says it
  }
  if (r.status == upload::UploadStatus::Interrupted) {
    ctx.err << "seqc: " << terminal_safe(p.name) << ": " << r.message << "\n";
    return ExitCode::Interrupted;
  }
  if (!r.ok()) return fail(ctx, ExitCode::DeviceFailure, terminal_safe(p.name) + ": " + r.message);
  summarize(ctx, terminal_safe(p.name) + ": the controller acknowledged " +
                     plural(r.actions_acknowledged, "action"));
  return ExitCode::Ok;
}

// "GroupRun 2 arrived 0.00 ms after the start (written 7.29 ms before it, 7.29 ms on the
// wire); the controller reported it started", or a streamed performer's packets and their
// lateness.
std::string start_text(const Stage& s, const boards::PerformerReport& p) {
  const io::Duration written = p.track.first.value_or(io::Duration{0});
  const std::string first = written < io::Duration{0} ? io::ms_text(-written, 2) + " before it"
                                                      : io::ms_text(written, 2) + " after it";
  const std::string started = io::ms_text(p.started().value_or(io::Duration{0}), 2);
  if (!p.run) {
    const player::LatenessSummary late = player::summarize(p.track.lateness);
    return std::to_string(p.track.sent) + " packets sent, the first arriving " + started +
           " after the start; lateness p50 " + io::ms_text(late.p50, 2) + ", p99 " +
           io::ms_text(late.p99, 2) + ", max " + io::ms_text(late.max, 2);
  }
  return std::string(s.board->run_name) + " " + std::to_string(s.performer->group) + " arrived " +
         started + " after the start (written " + first + ", " + io::ms_text(p.wire, 2) +
         " on the wire); " + run_said(*s.board, p.run);
}

ExitCode report_show(Context& ctx, const std::vector<Stage>& stages, const boards::ShowReport& r) {
  if (!r.error.empty()) return fail(ctx, ExitCode::Internal, r.error);
  switch (r.play.end) {
    case player::PlayEnd::Completed:
      break;
    case player::PlayEnd::Interrupted:
      ctx.err << "seqc: interrupted: stopped every performer\n";
      return ExitCode::Interrupted;
    case player::PlayEnd::WriteFailed:
      return fail(ctx, ExitCode::DeviceFailure,
                  terminal_safe(stages[r.play.failed_track.value_or(0)].performer->name) + ": " +
                      r.play.error + "; stopped every performer");
  }
  ExitCode code = ExitCode::Ok;
  for (std::size_t i = 0; i < stages.size(); ++i) {
    const boards::PerformerReport& p = r.performers[i];
    if (p.run && !p.run->ok()) {
      const Stage& s = stages[i];
      const BoardError e =
          outcome_text(*p.run, s.port->transport->describe(), kReplyTimeout, s.board->called);
      code = fail(ctx, e.code, terminal_safe(s.performer->name) + ": " + e.message);
      continue;
    }
    if (ctx.verbosity >= 0) {
      ctx.err << "seqc: " << terminal_safe(stages[i].performer->name) << ": "
              << start_text(stages[i], p) << "\n";
    }
  }
  summarize(ctx, "start skew between performers: " + io::ms_text(r.start_skew(), 2));
  return code;
}

struct ShowArgs {
  std::string file;
  bool strict = false;
  std::string trace;
  bool force = false;
  bool realtime = false;
  MusicArgs music;
};

ExitCode run_show(Context& ctx, const ShowArgs& args) {
  const std::string& path = args.file;
  const MusicArgs& music_args = args.music;
  ExitCode loaded = ExitCode::Ok;
  compiler::ShowOutput show = load_show_and_report(ctx, path, args.strict, loaded);
  if (loaded != ExitCode::Ok) return loaded;
  stop_cleanly_from_now(ctx);
  MusicSession music;
  if (music_args.music) {
    const compiler::ShowSong found = compiler::show_song(show);
    const std::string why = compiler::no_one_song(show, found);
    if (!why.empty()) return usage_error(ctx, "--music: " + terminal_safe(why));
    if (const ExitCode e = open_music(ctx, *found.song, music_args, music); e != ExitCode::Ok) {
      return e;
    }
  }

  std::vector<Stage> stages(show.performers.size());
  for (std::size_t i = 0; i < stages.size(); ++i) {
    if (ExitCode c = open_stage(ctx, show.performers[i], stages[i], args.trace);
        c != ExitCode::Ok) {
      return c;
    }
  }
  for (Stage& s : stages) {
    if (s.board->plan == nullptr) continue;
    if (const ExitCode e = upload_stage(ctx, s); e != ExitCode::Ok) {
      ctx.err << "seqc: nothing was started\n";
      return e;
    }
  }
  // The robot may be anywhere: nothing starts if one performer's first move is too fast.
  if (const auto unsafe =
          args.force ? std::nullopt : boards::first_unsafe_stage(stages, ctx.interrupted)) {
    ctx.err << "seqc: error: " << terminal_safe(stages[unsafe->stage].performer->name) << ": "
            << first_move_text(unsafe->too_fast) << "\n";
    ctx.err << "seqc: nothing was started\n";
    return ExitCode::InvalidInput;
  }
  if (ctx.verbosity >= 0) {
    ctx.err << "seqc: show " << terminal_safe(show.name) << ": starting "
            << plural(stages.size(), "performer") << " at one instant\n";
  }
  std::vector<boards::Performer> performers = boards::performers_of(stages);
  std::optional<io::TimePoint> start_at;
  std::optional<audio::StartPlan> plan;
  // From the song's start, whose playback clock dates the downbeat, to the performance's end.
  auto realtime = realtime_stretch(ctx, args.realtime);
  if (music_args.music) {
    if (!start_music(ctx, music)) {
      ctx.err << "seqc: nothing was started\n";
      return ExitCode::PortUnavailable;
    }
    // The performers' wire times are the show's; the song's instant is the common start.
    plan = boards::live_song_start(*stages[0].board, music, 0, 0, ctx.clock, ctx.clock).plan;
    start_at = plan->downbeat_heard;
  }
  const boards::ShowReport report =
      boards::perform(performers, ctx.clock, ctx.interrupted, kReplyTimeout, start_at);
  realtime.reset();
  if (plan && report.error.empty() && ctx.verbosity >= 0) {
    ctx.err << "seqc: " << heard_text(music, *plan)
            << "; each performer's start below is from it\n";
  }
  const ExitCode code = report_show(ctx, stages, report);
  if (!music_args.music) return code;
  if (code != ExitCode::Ok) return code;  // the song stops with `music`
  if (!boards::play_song_out(music, ctx.clock, ctx.interrupted)) {
    boards::stop_stages(stages);
    ctx.err << "seqc: interrupted: stopped the song and every performer\n";
    return ExitCode::Interrupted;
  }
  return ExitCode::Ok;
}

}  // namespace

void add_show_command(CLI::App& app, Context& ctx, Outcome& result) {
  auto o = std::make_shared<ShowArgs>();
  CLI::App* cmd = app.add_subcommand(
      "show", "Perform a show: upload every stored performer, then start all at one instant");
  cmd->add_option("FILE", o->file, "Show file (.yaml: show, performers)")->required();
  cmd->add_flag("--strict", o->strict, "Treat warnings as errors");
  add_trace_option(*cmd, o->trace,
                   "Write every byte exchanged with each performer's board, with times, to "
                   "PREFIX-NAME.trace (docs/trace.md; `seqc decode` reads each)");
  cmd->add_flag("--force", o->force,
                "Start even if a performer's first move is too fast from where its "
                "servos are");
  add_realtime_option(*cmd, o->realtime,
                      "Start and perform with real-time (SCHED_FIFO) priority, so a busy machine "
                      "cannot delay the start or streamed frames");
  add_music_options(*cmd, o->music);
  cmd->callback([&ctx, &result, o] { result.code = run_show(ctx, *o); });
}

}  // namespace seqc::cli
