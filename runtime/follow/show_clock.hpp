// Where a show's master clock says the dance is: the seam between what `seqc follow` listens
// to (FPP MultiSync packets, SMPTE timecode on an audio line) and what drives the robot.
//
// A ShowClock turns what it hears into events on the host's clock: Open (prepare: store the
// group, plan the stream) before Start; Start at dance time `dance_ms` (usually 0, later when
// the master started mid-file); Sync, the master's position now, as often as it says it; Stop.
// The follower (runtime/follow/follower.hpp) anchors the dance on Start, measures the offset on
// every Sync and corrects where the board lets it; a Stop, or next() reporting the end, stops
// the robot. `at` is when the master's reading was true on the host's clock, with the
// transport's latency already taken away where the source knows it.
#pragma once

#include <optional>
#include <string>

#include "runtime/io/clock.hpp"

namespace seqc::follow {

enum class ShowClockKind { Open, Start, Sync, Stop };

struct ShowClockEvent {
  ShowClockKind kind = ShowClockKind::Sync;
  double dance_ms = 0;  // the master's position in the dance, its time 0 the dance's
  io::TimePoint at{};   // the host instant at which that position was true
  std::string detail;   // for a person: "sync packet from 192.168.1.10", "locked at 25 fps"
};

class ShowClock {
 public:
  virtual ~ShowClock() = default;
  // The next event, waiting at most until `deadline` on the clock it was made with; nullopt
  // when none came by then. `ended` becomes true when the source has nothing more to say (the
  // socket failed, the WAV file ended, the input closed).
  virtual std::optional<ShowClockEvent> next(io::TimePoint deadline) = 0;
  virtual bool ended() const = 0;
};

}  // namespace seqc::follow
