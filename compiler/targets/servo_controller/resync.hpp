// `--resync BARS`: a long stored dance cut into pieces the computer starts one by one, so the
// board's clock can drift only within a piece. Piece k begins at the action boundary nearest the
// (k x BARS)-th bar line (on the bar line itself when a step starts there); its actions are
// rebased to start at 0, and the host starts it at the boundary's time on the host's clock: the
// boundary's board time divided by (1 + clock_ppm / 1e6), the inverse of the pre-scaling
// (CompileOptions::clock_ppm). Pure: keyframes and the tempo map in, pieces out.
#pragma once

#include <cstdint>
#include <vector>

#include "compiler/program/program.hpp"
#include "compiler/timeline/exact_time.hpp"
#include "base/result.hpp"

namespace seqc::compiler {

struct ResyncPiece {
  compiler::ExactMs host_start;               // when the host starts it, from the dance's start
  std::uint32_t board_start_ms = 0;           // where it was cut, on the board's timeline
  std::vector<compiler::Keyframe> keyframes;  // start_ms rebased to 0
};

// Errors: bars of 0, a dance without a tempo and meter (no bar lines), a cut that leaves a piece
// without actions never happens (cuts that meet are merged).
Result<std::vector<ResyncPiece>> split_at_bars(const compiler::ServoProgram& program,
                                               std::uint32_t bars, std::int32_t clock_ppm = 0);

}  // namespace seqc::compiler
