// seqc show SHOW.yaml: several performers on one clock (compiler/lang/show.hpp). Every file is
// checked first; then each stored performer's group is uploaded (progress per performer), and
// nothing starts unless every upload completed. Then everything starts at one instant: a
// single schedule, on ctx.clock's absolute deadlines, holds each stored performer's GroupRun at
// t = 0 and each streamed performer's packets at their times; frames for different ports are
// written in that one loop, so "one instant" is one deadline, not several programs' guesses.
// The report gives each performer's start (how long after the common deadline its first frame
// went out), the skew between performers, and the lateness of streamed frames.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "compiler/backend/raspblock_stream.hpp"
#include "compiler/backend/servo_backend.hpp"
#include "compiler/lang/show.hpp"
#include "runtime/cli/board_port.hpp"
#include "runtime/cli/commands.hpp"
#include "runtime/cli/compile_report.hpp"
#include "runtime/cli/group_dialect.hpp"
#include "runtime/cli/port_open.hpp"
#include "runtime/player/player.hpp"
#include "runtime/upload/controller_link.hpp"
#include "runtime/upload/progress_text.hpp"
#include "runtime/upload/uploader.hpp"

namespace seqc::cli {
namespace {

struct Stage {  // one performer, opened
  const compiler::Performer* performer = nullptr;
  std::optional<OpenedPort> controller;  // a stored performer
  std::optional<OpenedBoard> board;      // a streamed one
  io::Transport* transport = nullptr;
  std::vector<io::Duration> lateness;
  std::optional<io::Duration> first;  // when its first frame went out, after the start
  std::size_t frames = 0;
};

struct Cue {
  io::Duration at{0};
  std::size_t stage = 0;
  Bytes bytes;
};

std::string ms(io::Duration d) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f ms", std::chrono::duration<double, std::milli>(d).count());
  return buf;
}

ExitCode open_stage(Context& ctx, const compiler::Performer& p, Stage& stage) {
  stage.performer = &p;
  if (p.port.empty()) {
    ctx.err << "seqc: error: performer '" << p.name << "' has no port in the show file\n";
    return ExitCode::Usage;
  }
  if (p.output.servo_program() != nullptr) {
    PortOpenResult opened = open_controller_port(p.port, ctx);
    if (!opened.port) {
      ctx.err << "seqc: error: " << p.name << ": " << opened.failure.message << "\n";
      return opened.failure.code;
    }
    stage.controller = std::move(opened.port);
    stage.transport = stage.controller->transport.get();
    return ExitCode::Ok;
  }
  ExitCode code = ExitCode::Ok;
  auto board = open_board_port(p.port, p.file, ctx, code);
  if (!board) {
    ctx.err << "seqc: error: " << p.name << ": " << board.error().message << "\n";
    return code;
  }
  stage.board = std::move(*board);
  stage.transport = stage.board->link.get();
  return ExitCode::Ok;
}

// Stores a performer's group; false (with the reason said) if it did not complete.
bool upload_stage(Context& ctx, Stage& stage) {
  const compiler::Performer& p = *stage.performer;
  auto planned =
      backend::plan_download(*p.output.servo_program(), static_cast<std::uint8_t>(p.group));
  if (!planned) {
    ctx.err << "seqc: error: " << p.name << ": " << planned.error().message << "\n";
    return false;
  }
  const std::unique_ptr<GroupDialect> dialect = dialect_for(std::move(planned).value());
  if (ctx.verbosity >= 0) {
    ctx.err << "seqc: " << p.name << ": uploading " << p.output.servo_program()->keyframes.size()
            << " actions into group " << p.group << " on " << stage.transport->describe() << "\n";
  }
  upload::UploadOptions options;
  options.group = static_cast<std::uint8_t>(p.group);
  upload::ProgressPrinter progress(ctx.err, ctx.err_is_terminal, ctx.verbosity,
                                   ctx.terminal_columns);
  const upload::UploadResult r = dialect->upload(*stage.transport, *stage.controller->clock,
                                                 ctx.interrupted, options, &progress);
  progress.finish();
  if (!r.ok()) {
    ctx.err << "seqc: error: " << p.name << ": " << r.message << "\n";
    return false;
  }
  summarize(ctx, p.name + ": the controller acknowledged " +
                     std::to_string(r.actions_acknowledged) + " actions");
  return true;
}

ExitCode perform(Context& ctx, std::vector<Stage>& stages) {
  std::vector<Cue> cues;
  for (std::size_t i = 0; i < stages.size(); ++i) {
    const compiler::Performer& p = *stages[i].performer;
    if (stages[i].controller) {
      auto run = lsc::encode_serial(lsc::GroupRun{static_cast<std::uint8_t>(p.group), 1});
      cues.push_back({io::Duration{0}, i, run ? *run : Bytes{}});
    } else {
      auto frames = backend::plan_stream(*p.output.raspblock_program());
      if (!frames) return ExitCode::Internal;
      for (const auto& f : *frames)
        cues.push_back({std::chrono::milliseconds(f.at_ms), i, f.bytes});
    }
  }
  std::stable_sort(cues.begin(), cues.end(),
                   [](const Cue& a, const Cue& b) { return a.at < b.at; });
  io::Clock& clock = ctx.clock;
  // A short lead so the first deadline is in the future for every performer.
  const io::TimePoint start = clock.now() + std::chrono::milliseconds(20);
  for (const Cue& c : cues) {
    const io::TimePoint deadline = start + c.at;
    while (clock.now() < deadline) {
      if (ctx.interrupted != nullptr && ctx.interrupted->load()) break;
      clock.sleep_until(std::min(deadline, clock.now() + std::chrono::milliseconds(20)));
    }
    if (ctx.interrupted != nullptr && ctx.interrupted->load()) {
      for (Stage& s : stages) {  // the safe state: groups stopped, the car at zero speed
        auto stop = s.controller ? lsc::encode_serial(lsc::GroupStop{})
                                 : Result<Bytes>(backend::stop_frame());
        if (stop) (void)s.transport->write(*stop);
      }
      ctx.err << "seqc: interrupted: stopped every performer\n";
      return ExitCode::Interrupted;
    }
    Stage& s = stages[c.stage];
    const io::TimePoint before = clock.now();
    if (auto ok = s.transport->write(c.bytes); !ok) {
      ctx.err << "seqc: error: " << s.performer->name << ": " << ok.error().message << "\n";
      return ExitCode::DeviceFailure;
    }
    s.lateness.push_back(before - deadline);
    if (!s.first) s.first = before - start;
    ++s.frames;
  }
  return ExitCode::Ok;
}

ExitCode run_show(Context& ctx, const std::string& path, bool strict) {
  ExitCode loaded = ExitCode::Ok;
  compiler::ShowOutput show = load_show_and_report(ctx, path, strict, loaded);
  if (loaded != ExitCode::Ok) return loaded;

  std::vector<Stage> stages(show.performers.size());
  for (std::size_t i = 0; i < stages.size(); ++i) {
    if (ExitCode c = open_stage(ctx, show.performers[i], stages[i]); c != ExitCode::Ok) return c;
  }
  for (Stage& s : stages) {
    if (s.controller && !upload_stage(ctx, s)) {
      ctx.err << "seqc: nothing was started\n";
      return ExitCode::DeviceFailure;
    }
  }
  if (ctx.verbosity >= 0) {
    ctx.err << "seqc: show " << show.name << ": starting " << stages.size()
            << " performers at one instant\n";
  }
  const ExitCode code = perform(ctx, stages);
  if (code != ExitCode::Ok) return code;
  io::Duration earliest = io::Duration::max(), latest = io::Duration::min();
  for (const Stage& s : stages) {
    earliest = std::min(earliest, *s.first);
    latest = std::max(latest, *s.first);
    if (ctx.verbosity < 0) continue;
    const player::LatenessSummary late = player::summarize(s.lateness);
    ctx.err << "seqc: " << s.performer->name << ": "
            << (s.controller ? "GroupRun " + std::to_string(s.performer->group) + " sent"
                             : std::to_string(s.frames) + " packets sent, the first")
            << " " << ms(*s.first) << " after the start"
            << (s.controller ? std::string()
                             : "; lateness p50 " + ms(late.p50) + ", p99 " + ms(late.p99) +
                                   ", max " + ms(late.max))
            << "\n";
  }
  summarize(ctx, "start skew between performers: " + ms(latest - earliest));
  return ExitCode::Ok;
}

}  // namespace

void add_show_command(CLI::App& app, Context& ctx, Outcome& result) {
  struct Options {
    std::string file;
    bool strict = false;
  };
  auto o = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand(
      "show", "Perform a show: upload every stored performer, then start all at one instant");
  cmd->add_option("FILE", o->file, "Show file (.yaml: show, performers)")->required();
  cmd->add_flag("--strict", o->strict, "Treat warnings as errors");
  cmd->callback([&ctx, &result, o] { result.code = run_show(ctx, o->file, o->strict); });
}

}  // namespace seqc::cli
