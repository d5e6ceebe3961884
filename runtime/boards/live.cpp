#include "runtime/boards/live.hpp"

#include <algorithm>
#include <chrono>
#include <utility>

#include "compiler/formats/program_views.hpp"

namespace seqc::boards {
namespace {

// How often Ctrl-C is looked at while the last move finishes.
constexpr io::Duration kPollInterval = std::chrono::milliseconds(20);

bool interrupted(const Line& line) {
  return line.interrupted != nullptr && line.interrupted->load();
}

}  // namespace

LiveReport play_live(const Board& board, const compiler::CompileOutput& output, const Line& line,
                     bool allow_late, const LiveHooks& hooks) {
  LiveReport report;
  if (board.live_frames == nullptr) {
    report.status = LiveStatus::BadProgram;
    report.error = std::string(board.name) + " plays nothing live";
    return report;
  }
  auto frames = board.live_frames(output);
  if (!frames) {
    report.status = LiveStatus::BadProgram;
    report.error = frames.error().message;
    return report;
  }
  report.frames = std::move(frames).value();
  if (const compiler::ServoProgram* p = output.servo_program();
      p != nullptr && p->keyframes.size() == report.frames.size()) {
    for (const compiler::Keyframe& k : p->keyframes)
      report.origins.push_back({k.start_ms, k.source});
  }
  // The last move ends then, not when it is sent.
  report.length_ms = output.program ? compiler::length_ms(*output.program) : 0;
  const io::Duration length = std::chrono::milliseconds(report.length_ms);
  io::Transport& transport = line.transport;

  // Nothing is sent when one frame cannot go over the link at all.
  if (const std::size_t limit = transport.max_frame_bytes(); limit > 0) {
    for (std::size_t i = 0; i < report.frames.size(); ++i) {
      if (report.frames[i].bytes.size() > limit) {
        report.too_big = i;
        report.status = LiveStatus::FrameTooBig;
        return report;
      }
    }
  }
  if (board.check_schedule) {
    report.check = player::check_schedule(report.frames, transport.seconds_per_byte(),
                                          transport.frame_interval());
    if (report.check.first_late && !allow_late) {
      report.status = LiveStatus::LateSchedule;
      return report;
    }
  }
  if (hooks.checked) hooks.checked(report);

  if (board.probe != nullptr) {
    report.probe = board.probe(line);
    if (!report.probe.ok()) {
      report.status = LiveStatus::NoBoard;
      return report;
    }
  }
  if (hooks.starting) hooks.starting(report);

  player::PlayOptions options;
  options.interrupted = line.interrupted;
  if (board.safe_stop != nullptr) options.safe_stop = board.safe_stop();
  options.drain = board.measure_departure;
  options.seconds_per_byte = transport.seconds_per_byte();
  if (hooks.start) {
    const std::optional<LiveStart> start = hooks.start(report);
    if (!start) {
      report.status = LiveStatus::NotStarted;
      return report;
    }
    options.start_at = start->at;
    options.early = start->early;
  }
  options.on_sent = [&](std::size_t i, const player::FrameTiming&) {
    if (hooks.sent) hooks.sent(i, report.frames[i].at);
  };
  report.play = player::play(report.frames, transport, line.clock, options);

  switch (report.play.end) {
    case player::PlayEnd::Completed:
      break;
    case player::PlayEnd::Interrupted:
      report.status = LiveStatus::Interrupted;
      return report;
    case player::PlayEnd::WriteFailed:
      report.status = LiveStatus::WriteFailed;
      return report;
  }
  if (board.wait_for_end) {
    // The last move is still running: return when the sequence ends, so "played" means the
    // robot is in its final pose (and the next command sees it there).
    const io::TimePoint end = report.play.started + length;
    while (line.clock.now() < end) {
      if (interrupted(line)) {
        report.status = LiveStatus::InterruptedAtEnd;
        return report;
      }
      line.clock.sleep_until(std::min(end, line.clock.now() + kPollInterval));
    }
  }
  report.status = LiveStatus::Played;
  return report;
}

}  // namespace seqc::boards
