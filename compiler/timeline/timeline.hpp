// The timeline: what the author meant, per servo, on exact time, before anything is rounded or
// cut into controller actions. The front end appends segments as it walks the steps; fitting
// (compiler/fitting/) turns the whole timeline into the fewest actions that stay within each
// segment's tolerance, and `seqc simulate --compare` / `seqc plot` read it as the intended curve.
//
// A servo's segments are in time order and do not overlap. Between segments (and after the
// last) the servo holds its last value; before its first segment its position is unknown.
// A segment is either a hold (the servo is named and re-sent, as by `wait`), a straight line,
// an eased move, or one piece of a C1 cubic Hermite curve (`through`).
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "compiler/source/source.hpp"
#include "compiler/timeline/easing.hpp"
#include "compiler/timeline/exact_time.hpp"

namespace seqc::compiler {

enum class CurveKind { Hold, Linear, Eased, Hermite };

struct Segment {
  ExactMs start;  // absolute, from the start of the sequence
  ExactMs end;
  double from = 0;  // device units (not rounded)
  double to = 0;
  CurveKind kind = CurveKind::Linear;
  Easing easing;                        // Eased
  double slope_from = 0, slope_to = 0;  // Hermite: units per millisecond at start and end
  double tolerance = 1;                 // device units, at any instant of this segment
  bool keep_boundaries = false;         // `steps:` pieces: the boundaries are actions, never merged
  Location at;                          // the step (or waypoint) it comes from

  bool is_straight() const { return kind == CurveKind::Hold || kind == CurveKind::Linear; }
  // The intended position at absolute time t (ms), clamped to the segment.
  double value(double t_ms) const;
};

// A named moment for plots and listings: a section starting, an `at:` cue, a tempo change.
struct TimelineMarker {
  ExactMs at;
  std::string label;
  Location where;
};

struct Timeline {
  std::vector<std::vector<Segment>> servos;  // by output index (the robot's servo order)
  std::vector<TimelineMarker> markers;
  ExactMs end;  // when the last step ends
  // Tempo and meter in force at the start, for the beat/bar grid of plots (0 = none).
  double tempo = 0;
  int beats_per_bar = 0;

  // The intended position of `servo` at t, or nullopt while it is still unknown.
  std::optional<double> value(std::size_t servo, double t_ms) const;
};

}  // namespace seqc::compiler
