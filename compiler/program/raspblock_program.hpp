// What a choreography for the Yahboom Raspblock car board compiles to: a timed packet stream.
//
// The board stores nothing and answers nothing, so the program is the list of packets seqc
// plays on the host's clock (`seqc play`), each with its send time from the start of the play.
// compiler/targets/raspblock/raspblock_stream.hpp turns it into wire bytes; docs/raspblock.md is
// the language it comes from.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "base/source.hpp"
#include "compiler/timeline/timeline.hpp"
#include "protocol/raspblock/raspblock.hpp"

namespace seqc::compiler {

struct TimedPacket {
  std::uint32_t at_ms = 0;   // send time from the start of the play
  raspblock::Packet packet;  // already range-checked: raspblock::encode accepts it
  Location source;           // the step (or the `pid` section) it came from
};

struct RaspblockProgram {
  // Send order; at_ms never decreases. Never empty: the last packet is always the stop
  // (Rocker 0,0,0) at duration_ms, so a completed play leaves the car standing.
  std::vector<TimedPacket> packets;
  std::uint32_t duration_ms = 0;  // when the last step ends
  // The intended curves of the six positional outputs (pan, tilt, servo1-servo4, in that
  // order), the same timeline the arm's moves become; the packets sample it.
  Timeline timeline;
};

}  // namespace seqc::compiler
