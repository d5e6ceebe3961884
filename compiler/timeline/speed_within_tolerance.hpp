// The least peak speed of any motion that keeps within a tolerance of a segment's curve, starts
// where the curve starts and ends where it ends: what a controller that keeps the tolerance
// must reach at least, and can keep to. A curve that is vertical somewhere (circ, some
// cubic-beziers) has no finite peak of its own, yet this bound is finite: within the tolerance
// the vertical end can be cut short.
//
// In one dimension a motion within the band [x(t) - tol, x(t) + tol] (the ends pinned to the
// curve) with speed at most L exists exactly when, for every two instants s < t,
// (low(t) - high(s)) / (t - s) <= L and (low(s) - high(t)) / (t - s) <= L; the bound is the
// largest of those quotients. For circ-in over A units in T with tolerance tol it is
// (A^2 - tol^2) / (2 tol T): the line from the end, tangent to the band's lower edge.
#pragma once

#include "compiler/timeline/timeline.hpp"

namespace seqc::compiler {

// Units per second; `tolerance` in device units (> 0). Cost: some 5,000 evaluations of the curve
// and a hull over them, whatever the segment's length.
double speed_within_tolerance(const Segment& segment, double tolerance);

}  // namespace seqc::compiler
