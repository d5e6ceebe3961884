// A dance longer than one group, cut into consecutive groups the computer starts one after the
// other (`seqc upload --run`). Each group ends on the last bar line it can hold, so that the
// fewest groups are used and each starts exactly on its bar: where an action already ends on
// that bar line nothing is added; where one runs across it, it is cut in two there (one action
// more, the wasted one), with the servos' positions at the cut on whole units chosen so that
// both halves stay within every servo's tolerance of the intended curve at every millisecond
// under the controller model. A bar line inside an action that cannot be cut so (a first move
// from an unknown position, a half shorter than the shortest action, a cut that would leave the
// tolerance) is not a candidate. A dance without bar lines (no tempo and meter) is cut at
// action boundaries, on a section's start where one lies within the last group's reach.
//
// Pure: the program in, pieces (the same as `--resync`'s, compiler/targets/servo_controller/
// resync.hpp) out; every cut's exact host time is its bar line's (or the boundary's board time
// divided by the clock's pre-scaling). Cost: the actions, plus the milliseconds of the few
// actions it tries to cut, never the dance's length.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "base/result.hpp"
#include "compiler/program/program.hpp"
#include "compiler/targets/servo_controller/resync.hpp"

namespace seqc::compiler {

struct ChainCut {
  std::vector<ResyncPiece> pieces;
  std::vector<std::int64_t> bars;  // by piece: the bar (counted from 1) it starts on; 0 = none
  std::size_t split_actions = 0;   // actions cut in two on a bar line
};

// `capacity`: actions one group holds. Errors: capacity 0, an empty program, and a stretch
// between two candidates longer than a group holds (said with its time and bar).
Result<ChainCut> chain_groups(const ServoProgram& program, std::size_t capacity,
                              std::int32_t clock_ppm = 0);

}  // namespace seqc::compiler
