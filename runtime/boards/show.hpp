// A show: several boards started on one deadline. Each performer is one track of one player:
// a board that stores its group gets its run frame at the common start, a streamed board gets
// its live frames from the same start. After an early end every track's safe stop is written.
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
  std::optional<RunOutcome> run;  // stored performers
};

struct ShowReport {
  player::PlayReport play;
  std::vector<PerformerReport> performers;
  // Not empty when a streamed performer's frames could not be made: nothing was sent.
  std::string error;
};

ShowReport perform(std::vector<Performer>& performers, io::Clock& clock,
                   const std::atomic<bool>* interrupted, io::Duration reply_timeout);

}  // namespace seqc::boards
