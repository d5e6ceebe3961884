// The deadline scheduler behind `seqc play`: sends timed frames to a device that keeps no
// program of its own (the Raspblock board; live play on the servo controller later).
//
// Frame i is written when the injected clock reaches start + at_i, where start is the clock's
// time when play() begins. Deadlines are absolute, so a late wake-up or a slow write delays
// only the frames already due, never the ones after them: lateness does not accumulate.
// The player never reads the wall clock or sleeps by itself (io::Clock does both), so tests
// run it on io::ManualClock without waiting.
//
// Safety: when a play ends early (the interrupted flag is set, or a write fails), the player
// sends options.safe_stop, if given, before returning.
#pragma once

#include <atomic>
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "runtime/io/clock.hpp"
#include "runtime/io/transport.hpp"
#include "runtime/protocol/bytes.hpp"

namespace seqc::player {

struct ScheduledFrame {
  io::Duration at{0};  // from the start of the play; never decreasing along a schedule
  Bytes bytes;
};

// How one frame went: lateness = when its write began - its deadline.
struct FrameTiming {
  io::TimePoint deadline{0};
  io::Duration lateness{0};
  io::Duration write_time{0};  // how long write() took
};

struct PlayOptions {
  const std::atomic<bool>* interrupted = nullptr;  // polled before each frame and while waiting
  std::optional<Bytes> safe_stop;                  // sent after an early end
  // Longest single sleep, so an interrupt is noticed within about this long.
  io::Duration poll_interval = std::chrono::milliseconds(20);
  // Called after each frame is written (progress display, measurements).
  std::function<void(std::size_t index, const FrameTiming& timing)> on_sent;
};

enum class PlayEnd { Completed, Interrupted, WriteFailed };

struct PlayReport {
  PlayEnd end = PlayEnd::Completed;
  io::TimePoint started{0};
  std::size_t sent = 0;                // frames written in full
  std::vector<io::Duration> lateness;  // one per frame written, in order
  std::string error;                   // WriteFailed: why
  bool stop_sent = false;              // safe_stop was written after an early end
  std::string stop_error;              // why it could not be, if it was tried and failed
};

PlayReport play(const std::vector<ScheduledFrame>& frames, io::Transport& transport,
                io::Clock& clock, const PlayOptions& options = {});

// Percentiles of lateness (nearest rank) and the largest value; all zero when empty.
struct LatenessSummary {
  io::Duration p50{0};
  io::Duration p99{0};
  io::Duration max{0};
};
LatenessSummary summarize(std::vector<io::Duration> lateness);

}  // namespace seqc::player
