// The claw's tip against the table along every move of an arm's joints, whatever the move was
// written as (a tip move, a `path: line`, joint positions, eased, `steps`, `through`): the tip by
// the forward kinematics (program/arm_kinematics.hpp) of the joints' intended positions on the
// timeline, all four joints as every track leaves them, at every millisecond of the move. The
// end-point check of a `tip:` (servo_tip.cpp) sees only the point asked for; between its ends a
// move of the joints bows, and may take the claw through the table.
//
// What the move's own ends excuse: the tip may be as deep as where the move starts (the move
// before put it there, and was checked for it), as deep as its end when a `tip:` placed that end
// (its joints rounded to whole units may put a point on the table a little below it), and a
// `path: line`'s tip as far below as its tolerance (the line itself is never below the table).
//
// Cost: a move up to kEveryMsUpTo ms is sampled at every millisecond. A longer one is sampled at
// kLongSamples + 1 evenly spaced instants, and each sample counts as lower by a margin that covers
// the tip between samples: half the spacing times the tip's largest vertical speed (each of the
// shoulder, elbow and wrist's peak speed, times the links beyond it), so the depth it gives is
// never less than the true one. Pure: no diagnostics here; the caller words what it finds.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "base/source.hpp"
#include "compiler/program/arm_geometry.hpp"
#include "compiler/timeline/exact_time.hpp"
#include "compiler/timeline/timeline.hpp"

namespace seqc::compiler {

inline constexpr double kEveryMsUpTo = 10'000;
inline constexpr std::uint32_t kLongSamples = 10'000;

// A step that moved any of the arm's joints, from `start` to `end` on the timeline.
struct ArmMove {
  Instant start, end;
  Location at;                   // the step
  bool tip_end = false;          // its end was placed by a `tip:`
  double line_tolerance_mm = 0;  // a `path: line`'s tolerance
};

// The deepest a step's tip goes below the table, over every time the step was performed.
struct TipDip {
  Location at;
  double depth_mm = 0;            // below the table; a sampled move's includes its margin
  double at_ms = 0;               // when, on the timeline
  std::array<double, 3> point{};  // where the tip is then, mm
  double below_ms = 0;            // how long the tip is below the table in that performance
};

// `joints`: the servos of the base, shoulder, elbow and wrist. One dip per step that goes below
// the table (beyond what its ends excuse), in the order the steps were first performed.
std::vector<TipDip> find_tip_dips(const compiler::ArmGeometry& arm,
                                  const std::array<std::size_t, 4>& joints,
                                  const Timeline& timeline, const std::vector<ArmMove>& moves);

}  // namespace seqc::compiler
