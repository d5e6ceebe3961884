// Drives one robot from a ShowClock (show_clock.hpp): the robot's dance is kept on the master's
// clock, whatever the master is (FPP MultiSync, SMPTE timecode).
//
// Everything the robot is sent is a schedule of frames on dance time, anchored on the host's
// clock at the instant the dance's time 0 falls: the car's stream (a frame every step, timed by
// the host), or a servo controller's starts (the board's stop then its run of the group holding
// each piece; one piece, group `group`, unless `resync_bars` cuts the dance at bar lines or it is
// longer than one group). Open stores the group(s) (as `seqc upload`) or plans the stream; Start
// anchors the schedule at the event's `at` minus its `dance_ms`, plus `offset` (positive: the
// robot runs later); a Start before any Open prepares first.
//
// Every Sync measures the offset: the robot's dance time minus the master's at the same instant
// (positive: the robot is ahead). The car's stream is re-anchored when it is more than
// `reanchor_after` off: what the car should be doing at the new time (the latest frame of each
// kind before it) is sent at once and the rest follow on the new anchor, so a jump of any size is
// followed within one frame. A stored group cannot be moved while it plays: beyond
// `restart_after` the schedule is re-anchored and the next piece starts on its bar line on the
// master's time (a dance of one piece keeps its offset until the master starts it again). A start
// written late (a master's start cannot be foreseen by the start frame's wire time) counts as
// that much behind. A Stop sends the board's stop (the car's all-speeds-0 frame, the controller's
// group stop) and, unless `once`, the follower waits, still prepared, for the next Start (a
// looping playlist); the clock's end, an interrupt or a failed write stop the robot before
// returning.
//
// Returns data only; `hooks.note` receives lines for a person as they happen.
#pragma once

#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "compiler/compile.hpp"
#include "runtime/boards/board.hpp"
#include "runtime/follow/show_clock.hpp"
#include "runtime/io/clock.hpp"
#include "runtime/player/player.hpp"

namespace seqc::follow {

struct FollowerOptions {
  std::uint8_t group = 0;         // servo controller: the (first) group stored
  int retries = 4;                // the upload's re-sends of one frame
  std::uint32_t resync_bars = 0;  // servo controller: pieces of this many bars (0: one group)
  std::int32_t clock_ppm = 0;     // the board's clock error the dance was compiled for (--rig)
  io::Duration offset{0};         // --offset: positive, the robot runs later
  io::Duration reanchor_after = std::chrono::milliseconds(5);   // the car's stream
  io::Duration restart_after = std::chrono::milliseconds(100);  // a stored group
  io::Duration poll = std::chrono::milliseconds(20);  // longest wait, so interrupts are seen
  const std::atomic<bool>* interrupted = nullptr;
  // End at the master's first stop; else stay, prepared, for its next start (a looping
  // playlist) until interrupted.
  bool once = true;
};

enum class FollowEnd { Stopped, SourceEnded, Interrupted, PrepareFailed, WriteFailed };

inline constexpr std::size_t kMaxOffsets = 1'000'000;

struct FollowReport {
  FollowEnd end = FollowEnd::Stopped;
  std::string error;  // PrepareFailed, WriteFailed: why
  bool prepared = false;
  std::size_t groups = 0;       // servo controller: groups stored
  std::size_t starts = 0;       // Start events followed
  std::size_t stops = 0;        // Stop events followed
  std::size_t syncs = 0;        // Sync events measured
  std::size_t corrections = 0;  // re-anchors (car) or restarts scheduled (stored groups)
  std::size_t frames = 0;       // frames written (starts of pieces on a servo controller)
  // The robot's dance time minus the master's at each Sync, before any correction, in ms (the
  // first kMaxOffsets: a master that never stops cannot fill the memory).
  std::vector<double> offsets_ms;
  // How late the first frame after the first Start was written against its due instant.
  std::optional<io::Duration> first_late;
  bool stop_sent = false;
  std::string stop_error;
};

struct FollowerHooks {
  std::function<void(const std::string&)> note;
};

// The median and 99th percentile (nearest rank) of |offset|, in ms; zeros when empty.
struct OffsetSummary {
  double median = 0;
  double p99 = 0;
  double max = 0;
};
OffsetSummary summarize_offsets(std::vector<double> offsets_ms);

class Follower {
 public:
  // `host` is the clock the ShowClock dates its events on; the line's own clock serves the
  // board's exchanges (an in-process emulator keeps its own time).
  Follower(const boards::Board& board, const compiler::CompileOutput& output,
           const boards::Line& line, io::Clock& host, FollowerOptions options,
           FollowerHooks hooks = {});

  // Follows until a Stop, the clock's end, an interrupt or a failure.
  FollowReport run(ShowClock& clock);

  // The steps of run(), for tests and for commands that drive several followers.
  bool prepare();                        // false: report().error says why
  bool handle(const ShowClockEvent& e);  // false: the follow has ended
  bool send_due();                       // false: a write failed
  std::optional<io::TimePoint> next_due() const;
  void stop_robot();
  void finish(FollowEnd end);  // stops the robot and says how the follow ended
  const FollowReport& report() const { return report_; }
  const std::vector<player::ScheduledFrame>& schedule() const { return schedule_; }

 private:
  io::TimePoint due(std::size_t i) const;
  void anchor_at(io::TimePoint master_anchor, bool starting);
  bool within_limit(io::Duration off) const;  // no correction needed
  void say(const std::string& line) const;
  bool write(std::size_t i, io::TimePoint due_at);

  const boards::Board& board_;
  const compiler::CompileOutput& output_;
  const boards::Line& line_;
  io::Clock& host_;
  FollowerOptions options_;
  FollowerHooks hooks_;
  FollowReport report_;
  bool stream_ = false;  // the car: host-timed frames, re-anchored freely
  std::vector<player::ScheduledFrame> schedule_;
  std::optional<io::TimePoint> anchor_;        // the schedule's dance time 0 on the host clock
  std::optional<io::TimePoint> robot_anchor_;  // where the robot's dance time 0 really is
  std::size_t next_ = 0;
  std::vector<std::string> keys_;            // the stream: what each frame sets (state_key)
  std::vector<std::size_t> catch_up_;        // the stream: frames to send at once
  std::map<std::string, std::size_t> sent_;  // the stream: the last frame written of each key
};

// Several followers on one ShowClock (a show's performers, each on its own port): every event
// goes to each in turn and each one's due frames are sent. The clock's end, an interrupt, or
// with `once` a Stop, ends them all; so does one follower's failure (`failed` says whose; the
// others end Stopped). Every robot is stopped before it returns.
struct FollowAll {
  FollowEnd end = FollowEnd::Stopped;
  std::optional<std::size_t> failed;
};
FollowAll follow_all(std::span<Follower* const> followers, ShowClock& clock, io::Clock& host,
                     const std::atomic<bool>* interrupted, io::Duration poll, bool once);

}  // namespace seqc::follow
