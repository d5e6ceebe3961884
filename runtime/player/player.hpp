// The deadline scheduler behind `seqc play` and `seqc show`: sends timed frames to devices that
// play them as they arrive (the Raspblock car's stream, live moves on a servo controller), to one
// transport or to several at once (one Track each), all on one clock.
//
// One timing rule for every player: a frame finishes arriving at its time. Frame i is written
// when the injected clock reaches start + at_i - early - wire_i, where wire_i is its own wire
// time (its bytes x its track's seconds_per_byte), early is its track's constant (the board's
// start delay), and start is options.start_at or, without it, the clock's time when play()
// begins plus options.lead plus what the frame due furthest ahead of its `at` needs. So frames
// of different sizes keep their times against each other and against a song, rather than each
// arriving late by its own length. Deadlines are absolute, so a late wake-up or a slow
// write delays only the frames already due, never the ones after them: lateness does not
// accumulate. With several tracks the frames are merged by deadline; frames due at the same time
// go in track order, then frame order, so a show's performers start in the order they are listed.
// The player never reads the wall clock or sleeps by itself (io::Clock does both), so tests
// run it on io::ManualClock without waiting.
//
// Safety: when a play ends early (the interrupted flag is set, or a write fails), the player
// writes every track's safe_stop, if given, in track order, before returning: a failed write on
// one transport stops the others too.
#pragma once

#include <atomic>
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "base/bytes.hpp"
#include "runtime/io/clock.hpp"
#include "runtime/io/transport.hpp"

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
  io::Duration left_lateness{0};
  std::size_t track = 0;  // whose frame (always 0 for the single-transport play())
};

struct PlayOptions {
  const std::atomic<bool>* interrupted = nullptr;  // polled before each frame and while waiting
  std::optional<Bytes> safe_stop;  // single-transport play(): sent after an early end
  // Longest single sleep, so an interrupt is noticed within about this long.
  io::Duration poll_interval = std::chrono::milliseconds(20);
  // The common start is this long after play() begins: time to be asleep before the first
  // deadline, so the first frames are not late by the setup.
  io::Duration lead{0};
  // The common start at this instant instead (a song's downbeat as heard); lead is then unused.
  std::optional<io::TimePoint> start_at;
  // Single-transport play(): as Track::early.
  io::Duration early{0};
  // Called after each frame is written (progress display, measurements); `index` is the frame's
  // position within its own track.
  std::function<void(std::size_t index, const FrameTiming& timing)> on_sent;
  // Single-transport play(): wait for each frame to leave (Transport::drain) and measure
  // left_lateness.
  bool drain = false;
  // Single-transport play(): as Track::seconds_per_byte.
  double seconds_per_byte = 0;
};

// One transport's share of a play.
struct Track {
  io::Transport* transport = nullptr;
  std::vector<ScheduledFrame> frames;  // `at` from the common start, never decreasing
  std::optional<Bytes> safe_stop;      // written to this transport after an early end
  bool drain = false;                  // as PlayOptions::drain, for this transport
  // A frame's wire time is its size times this; each frame is written that long before its
  // `at` (0: the link takes no time, e.g. reports on a fixed interval).
  double seconds_per_byte = 0;
  // Every frame is written this much earlier still: the board's start delay.
  io::Duration early{0};
};

struct TrackReport {
  std::size_t sent = 0;                     // frames written in full
  std::vector<io::Duration> lateness;       // one per frame written, in order
  std::vector<io::Duration> left_lateness;  // with drain: one per frame written
  std::optional<io::Duration> first;        // when its first write began, after the start
                                            // (negative for a track written early)
  bool stop_sent = false;                   // its safe_stop was written after an early end
  std::string stop_error;                   // why it could not be, if it was tried and failed
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
  // The fields above are track 0's for the single-transport play(); for several tracks, sent
  // counts every track's frames, lateness and left_lateness are in writing order, and the
  // stop fields are the first track's that tried one.
  std::vector<TrackReport> tracks;          // one per track, in track order
  std::optional<std::size_t> failed_track;  // WriteFailed: whose write failed
};

// Every track's frames on one clock (see the top of this file).
PlayReport play(const std::vector<Track>& tracks, io::Clock& clock, const PlayOptions& options);
// One track, built from options (safe_stop, drain, seconds_per_byte).
PlayReport play(const std::vector<ScheduledFrame>& frames, io::Transport& transport,
                io::Clock& clock, const PlayOptions& options = {});

// The schedule checked against the link before playing: frame i is due to start leaving its own
// wire time before its `at` (as play() writes it), and cannot before frame i-1 has left (its
// bytes x seconds_per_byte, at least frame_interval apart), so it leaves late when the line is
// still busy when it is due. The first late frame, if any.
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
