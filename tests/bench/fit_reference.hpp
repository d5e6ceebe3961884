// The references fit_bench measures the fitter against, computed here independently of it:
// the intended curves (textbook easings and Hermite pieces in Bezier form), the exact minimum
// of one curve with free end points, the knots of a set of tracks as the language's rule makes
// them, a floor under any fit that keeps them, and the exact minimum for two servos. Each is a
// dynamic program over every (millisecond, whole unit) state: slow, and simple enough to trust.
#pragma once

#include <vector>

#include "compiler/timeline/easing.hpp"
#include "tests/compiler/easing_reference.hpp"

namespace seqc::compiler::fit_reference {

// One piece of a servo's intended motion, as this file evaluates it.
struct Piece {
  double t0 = 0, t1 = 0, from = 0, to = 0;
  bool hermite = false;
  double slope_from = 0, slope_to = 0;
  Easing easing;
  double at(double t) const {
    if (t <= t0) return from;
    if (t >= t1) return to;
    const double u = (t - t0) / (t1 - t0);
    if (!hermite) return from + (to - from) * testing::ease_ref::at(easing, u);
    const double h = t1 - t0;
    const double p1 = from + slope_from * h / 3, p2 = to - slope_to * h / 3;
    const double v = 1 - u;
    return v * v * v * from + 3 * v * v * u * p1 + 3 * v * u * u * p2 + u * u * u * to;
  }
};

// A servo's track: pieces back to back.
struct Track {
  std::vector<Piece> pieces;
  double at(double t) const {
    for (const Piece& p : pieces) {
      if (t <= p.t1) return p.at(t);
    }
    return pieces.back().to;
  }
};

// The exact fewest actions for one curve over [0, duration] with free end points (1 << 30 when
// none reaches the end).
int free_minimum(const Piece& p, int duration, double tol);
// The knots of a set of tracks as the fitter's documented rule makes them.
std::vector<int> knots_of(const std::vector<Track>& tracks, int end_ms);
// The fewest actions one servo needs over [a, b] on its own (pinned ends on request).
int interval_minimum(const Track& tr, int a, int b, double tol, bool pin_a, bool pin_b);
// A floor under any fit that keeps the knot rule.
long knot_floor(const std::vector<Track>& tracks, int end_ms, double tol);
// The exact fewest actions for two servos under the knot rule (-1 where a shortfall leaves none).
long exact_two_servo_minimum(const std::vector<Track>& tracks, int end_ms, double tol);

}  // namespace seqc::compiler::fit_reference
