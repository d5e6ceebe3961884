// The moves live play sends a servo controller (xArm family and LSC-6 alike): one per keyframe,
// sent at its start, carrying only the servos whose target changes. The first move carries every
// servo it names; after that a servo is left out while its target stays where the last move sent
// it (the move before has ended when the next one starts, so it is there already). At 9600 baud a
// six-servo MultiServoMove is 25 bytes (26 ms), a one-servo one 10 bytes, so dropping what does
// not change is what lets dense schedules leave on time. A keyframe in which nothing changes
// still leaves, with one servo sent where it already is, so every move keeps its time and play
// still ends when the last move does. The keyframes of an opening rest, before any servo is
// named, send nothing: the servos stay where they stand and the first move leaves on its time.
#pragma once

#include <cstdint>
#include <vector>

#include "compiler/compile.hpp"
#include "protocol/servo_target.hpp"

namespace seqc::boards {

struct LiveMove {
  std::uint32_t send_ms = 0;  // from the start of the sequence
  std::uint16_t time_ms = 0;
  std::vector<lsc::ServoTarget> targets;  // ascending id, each id once
};

std::vector<LiveMove> changed_moves(const compiler::ServoProgram& program);

}  // namespace seqc::boards
