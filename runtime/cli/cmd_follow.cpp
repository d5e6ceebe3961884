// seqc follow FILE_OR_SHOW --fpp NAME [--port P] [--listen ADDR[:PORT]] [--offset MS] [--resync
// BARS] [--restart-after MS] [--clock-ppm N] [--rig FILE] [--realtime] [--strict]
// seqc follow FILE_OR_SHOW --ltc SOURCE --start HH:MM:SS:FF [the same options but --listen]
// Joins a Falcon Player show as a MultiSync remote (runtime/follow/multisync_clock.hpp), or
// chases SMPTE timecode on an audio input (runtime/follow/ltc_clock.hpp, follow_ltc.hpp), and
// drives the robot on the master's clock (runtime/follow/follower.hpp): the group is stored, or
// the car's stream planned, when the master opens NAME (the timecode first locks), started when
// it starts (reaches --start), kept on its clock by its syncs (frames) and stopped when it stops.
// A show file's performers all follow, each on the port the show gives it. Every signal that
// ends seqc stops the robot.
#include <unistd.h>

#include <array>
#include <cstdio>
#include <deque>
#include <memory>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include <fmt/format.h>

#include <CLI/CLI.hpp>

#include "base/terminal_text.hpp"
#include "compiler/show.hpp"
#include "protocol/fpp_multisync.hpp"
#include "runtime/boards/board.hpp"
#include "runtime/boards/board_link.hpp"
#include "runtime/boards/show.hpp"
#include "runtime/cli/board_text.hpp"
#include "runtime/cli/clock_option.hpp"
#include "runtime/cli/commands.hpp"
#include "runtime/cli/compile_report.hpp"
#include "runtime/cli/follow_ltc.hpp"
#include "runtime/cli/realtime_option.hpp"
#include "runtime/cli/run_compile.hpp"
#include "runtime/cli/trace_option.hpp"
#include "runtime/cli/version.hpp"
#include "runtime/follow/follower.hpp"
#include "runtime/follow/multisync_clock.hpp"
#include "runtime/io/udp_socket.hpp"

namespace seqc::cli {
namespace {

constexpr std::uint64_t kLargestShowFile = 1 << 20;

struct FollowArgs {
  std::string file;
  std::string fpp;    // the master's sequence or media file to follow
  std::string ltc;    // or the audio input that carries timecode
  std::string start;  // the timecode of the dance's time 0
  std::string port;
  std::string listen = "0.0.0.0";
  double offset_ms = 0;
  double restart_after_ms = 100;
  unsigned resync = 0;
  int group = 0;
  bool strict = false;
  bool realtime = false;
  bool once = false;
  std::string trace;
  ClockScaleOptions clock;
};

std::string host_name() {
  std::array<char, 256> name{};
  if (::gethostname(name.data(), name.size() - 1) != 0 || name[0] == 0) return "seqc";
  return name.data();
}

// "1.2.0" -> 1, 2.
std::pair<std::uint16_t, std::uint16_t> version_numbers(const std::string& v) {
  unsigned major = 0, minor = 0;
  (void)std::sscanf(v.c_str(), "%u.%u", &major, &minor);
  return {static_cast<std::uint16_t>(major), static_cast<std::uint16_t>(minor)};
}

std::string ended_text(follow::FollowEnd end) {
  switch (end) {
    case follow::FollowEnd::Stopped:
      return "the master stopped";  // --once
    case follow::FollowEnd::SourceEnded:
      return "the socket failed";
    case follow::FollowEnd::Interrupted:
      return "interrupted";
    case follow::FollowEnd::PrepareFailed:
      return "the robot could not be prepared";
    case follow::FollowEnd::WriteFailed:
      return "writing to the robot failed";
  }
  return "ended";
}

// One robot to follow with: its name in a show (empty for a single file), its board, its line.
struct Robot {
  std::string name;
  const boards::Board* board = nullptr;
  const compiler::CompileOutput* output = nullptr;
  const boards::Line* line = nullptr;
  std::uint8_t group = 0;
};

// What the robots follow: FPP's MultiSync on a UDP socket, or timecode on an audio input.
struct Source {
  std::unique_ptr<io::DatagramSocket> socket;
  std::unique_ptr<follow::MultisyncClock> multisync;
  std::unique_ptr<follow::ShowClock> timecode;
  std::string text;  // "NAME from FPP on udp 0.0.0.0:32320", "timecode on SOURCE from START"

  follow::ShowClock& clock() {
    return multisync ? static_cast<follow::ShowClock&>(*multisync) : *timecode;
  }
};

// Opens what --fpp or --ltc names; on failure, the exit code it was worded with.
ExitCode open_source(Context& ctx, const FollowArgs& a, Source& source) {
  if (!a.ltc.empty()) {
    const Result<ltc::Timecode> start = parse_ltc_start(a.start);
    if (!start) return usage_error(ctx, start.error().message);
    Result<std::unique_ptr<follow::ShowClock>> clock = open_ltc_clock(a.ltc, *start, ctx);
    if (!clock) return fail(ctx, ExitCode::FileError, clock.error().message);
    source.timecode = std::move(*clock);
    source.text = "timecode on " + terminal_safe(a.ltc) + " from " + a.start;
    return ExitCode::Ok;
  }
  const Result<io::UdpAddress> listen = io::parse_udp_address(a.listen, fpp::kControlPort);
  if (!listen) return usage_error(ctx, "--listen " + listen.error().message);
  // Multicast only where the socket hears every interface; a --listen on one address is unicast
  // (and broadcast) to it.
  const bool any = listen->ip == std::array<std::uint8_t, 4>{0, 0, 0, 0};
  auto socket = io::open_udp_socket(
      *listen, any ? std::optional(fpp::kMulticastGroup) : std::nullopt, ctx.clock);
  if (!socket) return fail(ctx, ExitCode::PortUnavailable, socket.error().message);
  source.socket = std::move(*socket);
  follow::MultisyncOptions ms;
  ms.name = a.fpp;
  ms.hostname = host_name();
  ms.version = std::string("seqc ") + kVersion;
  std::tie(ms.major, ms.minor) = version_numbers(kVersion);
  source.multisync = std::make_unique<follow::MultisyncClock>(*source.socket, ctx.clock, ms);
  source.text = terminal_safe(a.fpp) + " from FPP on " + source.socket->describe();
  return ExitCode::Ok;
}

// Follows with every robot, and words the end.
ExitCode follow_robots(Context& ctx, const FollowArgs& a, Source& from, std::vector<Robot>& robots,
                       std::int32_t clock_ppm) {
  follow::ShowClock& source = from.clock();

  std::vector<std::unique_ptr<follow::Follower>> followers;
  std::vector<follow::Follower*> all;
  for (const Robot& robot : robots) {
    follow::FollowerOptions options;
    options.group = robot.group;
    options.resync_bars = a.resync;
    options.clock_ppm = clock_ppm;
    // As FPP's own Remote Offset: a positive offset runs the robot ahead of the master (the
    // follower's offset is how much later it runs).
    options.offset = io::Duration{static_cast<std::int64_t>(-a.offset_ms * 1e6)};
    options.restart_after = io::Duration{static_cast<std::int64_t>(a.restart_after_ms * 1e6)};
    options.interrupted = ctx.interrupted;
    options.once = a.once;
    follow::FollowerHooks hooks;
    const std::string who = robot.name.empty() ? "" : terminal_safe(robot.name) + ": ";
    hooks.note = [&ctx, who](const std::string& text) {
      if (ctx.verbosity >= 0) {
        ctx.err << "seqc: follow: " << who << text << "\n";
        ctx.err.flush();
      }
    };
    followers.push_back(std::make_unique<follow::Follower>(*robot.board, *robot.output, *robot.line,
                                                           ctx.clock, options, hooks));
    all.push_back(followers.back().get());
  }
  if (ctx.verbosity >= 0) {
    ctx.err << "seqc: following " << from.text << " for ";
    for (std::size_t i = 0; i < robots.size(); ++i) {
      ctx.err << (i == 0 ? "" : ", ")
              << (robots[i].name.empty() ? "" : terminal_safe(robots[i].name) + " on ")
              << robots[i].line->transport.describe();
    }
    ctx.err << "; Ctrl-C stops the robot" << (robots.size() > 1 ? "s" : "")
            << (a.once ? "" : " and ends") << "\n";
    ctx.err.flush();
  }
  const auto realtime = realtime_stretch(ctx, a.realtime);
  const follow::FollowAll end = follow::follow_all(all, source, ctx.clock, ctx.interrupted,
                                                   std::chrono::milliseconds(20), a.once);

  for (std::size_t i = 0; i < robots.size() && ctx.verbosity >= 0; ++i) {
    const follow::FollowReport& r = followers[i]->report();
    const std::string who = robots[i].name.empty() ? "" : terminal_safe(robots[i].name) + ": ";
    const follow::OffsetSummary s = follow::summarize_offsets(r.offsets_ms);
    ctx.err << fmt::format(
        "seqc: {}follow ended ({}): {} start(s), {} stop(s), {} sync(s), {} correction(s), {} "
        "frame(s) written; offset to the master median {:.1f} ms, p99 {:.1f} ms, max {:.1f} ms\n",
        who, ended_text(r.end), r.starts, r.stops, r.syncs, r.corrections, r.frames, s.median,
        s.p99, s.max);
    if (r.first_late) {
      ctx.err << fmt::format("seqc: {}the first frame after the start was written {:.2f} ms late\n",
                             who, std::chrono::duration<double, std::milli>(*r.first_late).count());
    }
    if (r.stop_sent) {
      ctx.err << "seqc: " << who << "sent the stop\n";
    } else if (!r.stop_error.empty()) {
      ctx.err << "seqc: " << who << "could not send the stop: " << r.stop_error << "\n";
    }
  }
  if (ctx.verbosity >= 0 && from.multisync) {
    const follow::MultisyncCounts& n = from.multisync->counts();
    ctx.err << fmt::format(
        "seqc: heard {} packet(s) about {}, {} about other files, {} ping(s) ({} answered), {} "
        "malformed, {} of other types\n",
        n.followed, terminal_safe(a.fpp), n.other_names, n.pings, n.answered, n.malformed,
        n.other_types);
  }
  const auto whose = [&](std::size_t i) {
    return robots[i].name.empty() ? std::string() : terminal_safe(robots[i].name) + ": ";
  };
  switch (end.end) {
    case follow::FollowEnd::Stopped:
      return ExitCode::Ok;
    case follow::FollowEnd::Interrupted:
      return ExitCode::Interrupted;
    case follow::FollowEnd::SourceEnded:
      if (!from.multisync) return ExitCode::Ok;  // the timecode's input ended (a WAV file)
      return fail(ctx, ExitCode::PortUnavailable,
                  "the UDP socket failed: " + from.multisync->counts().last_error);
    case follow::FollowEnd::PrepareFailed:
      return fail(ctx, ExitCode::DeviceFailure,
                  whose(*end.failed) + followers[*end.failed]->report().error);
    case follow::FollowEnd::WriteFailed:
      return fail(ctx, ExitCode::DeviceFailure,
                  whose(*end.failed) + "sending to " +
                      robots[*end.failed].line->transport.describe() +
                      " failed: " + followers[*end.failed]->report().error);
  }
  return ExitCode::Internal;
}

// A show file: every performer follows, each on its own port.
ExitCode follow_show(Context& ctx, const FollowArgs& a, Source& source) {
  if (!a.port.empty()) {
    return usage_error(ctx, "--port: a show's performers bring their own ports (" + a.file + ")");
  }
  ExitCode loaded = ExitCode::Ok;
  const compiler::ShowOutput show = load_show_and_report(ctx, a.file, a.strict, loaded);
  if (loaded != ExitCode::Ok) return loaded;
  stop_cleanly_from_now(ctx);
  std::vector<boards::ShowStage> stages(show.performers.size());
  std::deque<boards::Line> lines;  // the followers keep a reference to theirs
  std::vector<Robot> robots;
  for (std::size_t i = 0; i < show.performers.size(); ++i) {
    const compiler::Performer& p = show.performers[i];
    const boards::StageOpen o = boards::open_stage(p, "", ctx.clock, ctx.hooks, stages[i]);
    if (o.problem == boards::StageProblem::NoPort) {
      return usage_error(ctx,
                         "performer '" + terminal_safe(p.name) + "' has no port in the show file");
    }
    if (o.problem != boards::StageProblem::None) {
      const BoardError e = port_failure(o.failure, o.request, p.file);
      return fail(ctx, e.code, terminal_safe(p.name) + ": " + e.message);
    }
    boards::OpenedPort& port = *stages[i].port;
    lines.push_back(boards::Line{*port.transport, *port.clock, ctx.interrupted});
    robots.push_back(
        {p.name, stages[i].board, &p.output, &lines.back(), static_cast<std::uint8_t>(p.group)});
  }
  return follow_robots(ctx, a, source, robots, 0);
}

ExitCode run_follow(Context& ctx, const FollowArgs& a) {
  if (a.fpp.empty() == a.ltc.empty()) {
    return usage_error(ctx,
                       "follow needs exactly one of --fpp NAME (a Falcon Player show) and "
                       "--ltc SOURCE (SMPTE timecode)");
  }
  if (!a.ltc.empty() && a.start.empty()) {
    return usage_error(ctx, "--ltc needs --start HH:MM:SS:FF, the timecode of the dance's start");
  }
  if (a.ltc.empty() && !a.start.empty()) {
    return usage_error(ctx, "--start is the timecode of --ltc; FPP's master says when to start");
  }
  Source source;
  if (const ExitCode e = open_source(ctx, a, source); e != ExitCode::Ok) return e;
  // A show file is small: a larger file is a choreography, whose loader sees to its size.
  const std::optional<std::uint64_t> size = ctx.files.size(a.file);
  if (size && *size <= kLargestShowFile) {
    if (const Result<std::string> text = ctx.files.read(a.file);
        text && compiler::is_show_text(*text)) {
      return follow_show(ctx, a, source);
    }
  }
  Compiled c = compile_for_run(ctx, a.file, a.strict, a.port, &a.clock);
  if (c.code != ExitCode::Ok) return c.code;
  if (!c.output.program) return ExitCode::InvalidInput;
  const boards::Board& board = boards::board_for(c.output);

  stop_cleanly_from_now(ctx);
  boards::TraceFile trace;
  if (const ExitCode e = open_trace(ctx, trace, a.trace); e != ExitCode::Ok) return e;
  const boards::BoardLink link =
      boards::open_link({a.port, &board}, trace, ctx.clock, ctx.hooks, ctx.interrupted);
  if (!link.port) return say_port_failure(ctx, link, a.file);
  std::vector<Robot> robots = {
      {"", &board, &c.output, &*link.line, static_cast<std::uint8_t>(a.group)}};
  return follow_robots(ctx, a, source, robots, c.clock_ppm);
}

}  // namespace

void add_follow_command(CLI::App& app, Context& ctx, Outcome& result) {
  auto a = std::make_shared<FollowArgs>();
  CLI::App* cmd = app.add_subcommand(
      "follow",
      "Follow a show's master clock: the robot is prepared, started, kept in time and stopped\n"
      "as a Falcon Player (FPP) master plays a file (--fpp NAME), or as SMPTE timecode runs\n"
      "(--ltc SOURCE --start HH:MM:SS:FF); Ctrl-C stops the robot");
  cmd->add_option("FILE", a->file,
                  "Choreography file (.yaml), or a show file whose performers all follow")
      ->required();
  cmd->add_option("--fpp", a->fpp,
                  "Join the FPP show as a MultiSync remote and follow the master's sequence or "
                  "media file NAME (without an extension: either)");
  cmd->add_option("--ltc", a->ltc,
                  "Chase SMPTE linear timecode on SOURCE: a PulseAudio source (`default`, "
                  "NAME.monitor) or a WAV file");
  cmd->add_option("--start", a->start,
                  "With --ltc: the timecode at which the dance starts, HH:MM:SS:FF (HH:MM:SS;FF "
                  "for drop-frame)");
  cmd->add_option("--port", a->port,
                  "As for `seqc play`: the servo controller (default: the one connected; "
                  "emu:xarm) or the Raspblock's serial port (emu:raspblock)");
  cmd->add_option("--listen", a->listen,
                  "Where to hear the master: ADDR[:PORT] (default 0.0.0.0:32320, which also "
                  "joins FPP's multicast group 239.70.80.80)");
  cmd->add_option("--offset", a->offset_ms,
                  "Milliseconds to run the robot ahead of the master, as FPP's Remote Offset "
                  "(negative: behind)");
  cmd->add_option("--restart-after", a->restart_after_ms,
                  "Servo controller: restart at the next piece a group this many ms off "
                  "(default 100)")
      ->check(CLI::Range(1.0, 60000.0));
  cmd->add_option("--resync", a->resync,
                  "Servo controller: cut the dance every BARS bars into groups --group, --group "
                  "+ 1, ..., started at their bar lines on the master's clock")
      ->check(CLI::Range(1, 10000));
  cmd->add_option("--group", a->group, "Servo controller: the (first) group to store (0-254)")
      ->check(CLI::Range(0, 254));
  cmd->add_flag("--once", a->once,
                "End at the master's first stop (else stay for its next start until Ctrl-C)");
  add_clock_options(*cmd, a->clock);
  add_realtime_option(*cmd, a->realtime,
                      "Keep time with real-time (SCHED_FIFO) priority while following");
  add_trace_option(*cmd, a->trace);
  cmd->add_flag("--strict", a->strict, "Treat warnings as errors");
  cmd->callback([&ctx, &result, a] { result.code = run_follow(ctx, *a); });
}

}  // namespace seqc::cli
