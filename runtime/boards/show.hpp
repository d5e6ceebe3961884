// A show: several boards started on one deadline. Each performer is one track of one player:
// a board that stores its group gets its run frame at the common start, a streamed board gets
// its live frames from the same start. "At the start" means when the start command finishes
// arriving at the board plus the board's start delay, not when it is written: each track is
// written early by its first frame's wire time (bytes x 10 bits / baud: a 7-byte GroupRun at
// 9600 baud takes 7.29 ms, a 13-byte car packet at 115200 1.13 ms) and its board's
// start_delay. After an early end every track's safe stop is written.
// When the play completes, every stored performer's start is confirmed the board's own way;
// the replies are read after the streams end, from what the transport kept.
#pragma once

#include <atomic>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "compiler/compile.hpp"
#include "runtime/boards/board.hpp"
#include "runtime/boards/ports.hpp"
#include "runtime/io/clock.hpp"
#include "runtime/player/player.hpp"

namespace seqc::boards {

struct Performer {
  std::string name;
  const Board* board = nullptr;
  OpenedPort* port = nullptr;
  const compiler::CompileOutput* output = nullptr;
  std::uint8_t group = 0;
};

struct PerformerReport {
  player::TrackReport track;
  io::Duration wire{0};   // its first frame's time on the wire
  io::Duration delay{0};  // its board's start delay
  // When its first frame finished arriving plus the start delay, from the common start: when
  // it started moving.
  std::optional<io::Duration> started() const {
    if (!track.first) return std::nullopt;
    return *track.first + wire + delay;
  }
  std::optional<RunOutcome> run;  // stored performers
};

struct ShowReport {
  player::PlayReport play;
  std::vector<PerformerReport> performers;
  // Not empty when a streamed performer's frames could not be made: nothing was sent.
  std::string error;
};

// `start_at`: the common start at this instant (a song's downbeat as heard) instead of shortly
// after the call.
ShowReport perform(std::vector<Performer>& performers, io::Clock& clock,
                   const std::atomic<bool>* interrupted, io::Duration reply_timeout,
                   std::optional<io::TimePoint> start_at = std::nullopt);

}  // namespace seqc::boards
