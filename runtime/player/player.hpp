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

// How one frame went: lateness = when its write began - its deadline. With drain, also when
// its last byte had left compared with when it would have, written on time (its deadline plus
// its own wire time).
struct FrameTiming {
  io::TimePoint deadline{0};
  io::Duration lateness{0};
  io::Duration write_time{0};  // how long write() took
  io::Duration left_lateness{0};
};

struct PlayOptions {
  const std::atomic<bool>* interrupted = nullptr;  // polled before each frame and while waiting
  std::optional<Bytes> safe_stop;                  // sent after an early end
  // Longest single sleep, so an interrupt is noticed within about this long.
  io::Duration poll_interval = std::chrono::milliseconds(20);
  // Called after each frame is written (progress display, measurements).
  std::function<void(std::size_t index, const FrameTiming& timing)> on_sent;
  // Wait for each frame to leave (Transport::drain) and measure left_lateness; the frame's own
  // wire time is its size times `seconds_per_byte`.
  bool drain = false;
  double seconds_per_byte = 0;
};

enum class PlayEnd { Completed, Interrupted, WriteFailed };

struct PlayReport {
  PlayEnd end = PlayEnd::Completed;
  io::TimePoint started{0};
  std::size_t sent = 0;                     // frames written in full
  std::vector<io::Duration> lateness;       // one per frame written, in order
  std::vector<io::Duration> left_lateness;  // with drain: one per frame written
  std::string error;                        // WriteFailed: why
  bool stop_sent = false;                   // safe_stop was written after an early end
  std::string stop_error;                   // why it could not be, if it was tried and failed
};

PlayReport play(const std::vector<ScheduledFrame>& frames, io::Transport& transport,
                io::Clock& clock, const PlayOptions& options = {});

// The schedule checked against the link before playing: frame i cannot start leaving before
// frame i-1 has left (its bytes x seconds_per_byte, at least frame_interval apart), so it
// leaves late when the line is still busy at its deadline. The first late frame, if any.
struct ScheduleCheck {
  std::optional<std::size_t> first_late;  // index
  io::Duration late_by{0};                // how late it would start leaving
  io::Duration wire_time{0};              // the previous frame's time on the line
  std::size_t late_frames = 0;
  io::Duration worst{0};
};
ScheduleCheck check_schedule(const std::vector<ScheduledFrame>& frames, double seconds_per_byte,
                             io::Duration frame_interval);

// Percentiles of lateness (nearest rank) and the largest value; all zero when empty.
struct LatenessSummary {
  io::Duration p50{0};
  io::Duration p99{0};
  io::Duration max{0};
};
LatenessSummary summarize(std::vector<io::Duration> lateness);

}  // namespace seqc::player
