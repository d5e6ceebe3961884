// What the fitting tests share, computed independently of the fitter: timelines of segments
// written out (one servo's eased move), the controller's motion rebuilt from the actions alone
// (each named servo in a straight line to its target, others holding), the intended curve from the
// textbook formulas (easing_reference.hpp; Hermite pieces in Bezier form), and a proof that a
// shortfall is unavoidable (a search over every motion the controller could make around that
// instant).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "compiler/fitting/fitter.hpp"
#include "compiler/timeline/easing.hpp"
#include "compiler/timeline/timeline.hpp"
#include "tests/compiler/easing_reference.hpp"

namespace seqc::compiler::fitting_check {

inline constexpr std::int64_t kMinActionMs = 20;
inline constexpr double kHoldTolerance = 1;  // the tolerance of the hold before the curve

// A segment over [start, end] ms.
inline Segment segment(int start, int end, double from, double to, CurveKind kind,
                       const Easing& easing, double tol) {
  Segment seg;
  seg.start = ExactMs(start);
  seg.end = ExactMs(end);
  seg.from = from;
  seg.to = to;
  seg.kind = kind;
  seg.easing = easing;
  seg.tolerance = tol;
  return seg;
}

// One servo's eased move over [0, ms], nothing before or after it.
inline Timeline eased_move(double from, double to, int ms, const Easing& easing, double tol) {
  Timeline tl;
  tl.resize(1);
  tl.add(0, segment(0, ms, from, to, CurveKind::Eased, easing, tol));
  tl.end = ExactMs(ms);
  return tl;
}

// The controller's motion of one servo (0 unless named), rebuilt from the actions alone: during
// each action a straight line from where the servo is to the action's target, or a hold if the
// action does not name it.
class Motion {
 public:
  Motion(const std::vector<FittedAction>& actions, double start_value, std::size_t servo = 0) {
    double pos = start_value;
    for (const FittedAction& a : actions) {
      double to = pos;
      for (const FittedTarget& x : a.targets) {
        if (x.servo == servo) to = x.position;
      }
      pieces_.push_back(
          {static_cast<double>(a.start_ms), static_cast<double>(a.start_ms + a.time_ms), pos, to});
      pos = to;
    }
    start_value_ = start_value;
  }
  double at(double t) const {
    const auto it = std::lower_bound(pieces_.begin(), pieces_.end(), t,
                                     [](const Piece& p, double v) { return p.end < v; });
    if (it == pieces_.end()) return pieces_.empty() ? start_value_ : pieces_.back().to;
    if (t <= it->start) return it->from;
    return it->from + (it->to - it->from) * (t - it->start) / (it->end - it->start);
  }

 private:
  struct Piece {
    double start, end, from, to;
  };
  std::vector<Piece> pieces_;
  double start_value_ = 0;
};

// What the author meant: `from` held until the curve starts at t0, then the curve to t1, then
// `to` held; computed from the reference formulas.
struct Intended {
  double t0 = 0, t1 = 0, from = 0, to = 0, tolerance = 1;
  bool hermite = false;
  double slope_from = 0, slope_to = 0;  // Hermite, units per ms
  Easing easing;                        // otherwise

  double at(double t) const {
    if (t <= t0) return from;
    if (t >= t1) return to;
    const double u = (t - t0) / (t1 - t0);
    if (!hermite) return from + (to - from) * testing::ease_ref::at(easing, u);
    // A cubic Hermite piece is the Bezier curve with inner control points a third of the way
    // along each end's tangent.
    const double h = t1 - t0;
    const double p1 = from + slope_from * h / 3, p2 = to - slope_to * h / 3;
    const double v = 1 - u;
    return v * v * v * from + 3 * v * v * u * p1 + 3 * v * u * u * p2 + u * u * u * to;
  }
  double tolerance_at(std::int64_t t) const {
    return static_cast<double>(t) < t0 ? kHoldTolerance : tolerance;
  }
};

// Whether a straight line fits within tol of want at every point of a window (offsets 0..n-1),
// decided exactly: with a and b the line's values at the window's ends, each point bounds b
// from below and above by a linear function of a; eliminating b (Fourier-Motzkin) leaves
// bounds on a.
inline bool one_line_fits(const std::vector<double>& want, const std::vector<double>& tol) {
  const std::size_t n = want.size();
  if (n <= 2) return true;
  double a_lo = want[0] - tol[0], a_hi = want[0] + tol[0];
  struct Bound {
    double c, k;  // b >= c - k a (lower) or b <= c - k a (upper)
  };
  std::vector<Bound> lower, upper;
  for (std::size_t t = 1; t < n; ++t) {
    const double lambda = static_cast<double>(t) / static_cast<double>(n - 1);
    const double k = (1 - lambda) / lambda;
    lower.push_back({(want[t] - tol[t]) / lambda, k});
    upper.push_back({(want[t] + tol[t]) / lambda, k});
  }
  for (const Bound& l : lower) {
    for (const Bound& u : upper) {
      // l.c - l.k a <= u.c - u.k a  <=>  (l.k - u.k) a >= l.c - u.c
      const double k = l.k - u.k, c = l.c - u.c;
      if (k > 0) {
        a_lo = std::max(a_lo, c / k);
      } else if (k < 0) {
        a_hi = std::min(a_hi, c / k);
      } else if (c > 0) {
        return false;
      }
    }
  }
  return a_lo <= a_hi;
}

// Whether some motion the controller could make stays within tolerance of the intended curve
// at every millisecond of [l, r]: straight lines between breakpoints on the millisecond grid,
// at least kMinActionMs apart, each breakpoint at any whole unit within tolerance of the
// intended position there, and at a knot (the start, and each end of the curve: segment
// boundaries stay action boundaries) at the intended position rounded. The line entering the
// window and the one leaving it are allowed any slope and length (their other ends lie
// outside), so `false` proves that no motion does.
inline bool followable(const Intended& c, std::int64_t l, std::int64_t r) {
  const std::size_t n = static_cast<std::size_t>(r - l + 1);
  std::vector<double> want(n), tol(n);
  std::vector<int> lowest(n), highest(n);  // the whole units a breakpoint may be at
  std::vector<char> knot(n);
  std::size_t first_knot = n;
  for (std::size_t i = 0; i < n; ++i) {
    const std::int64_t t = l + static_cast<std::int64_t>(i);
    const double td = static_cast<double>(t);
    want[i] = c.at(td);
    tol[i] = c.tolerance_at(t) + 1e-7;  // generous: a proof must not hang on rounding noise
    knot[i] = t == 0 || td == c.t0 || td == c.t1;
    if (knot[i]) {
      lowest[i] = highest[i] = static_cast<int>(std::lround(want[i]));
    } else {
      lowest[i] = static_cast<int>(std::ceil(want[i] - tol[i]));
      highest[i] = static_cast<int>(std::floor(want[i] + tol[i]));
    }
    if (knot[i] && first_knot == n) first_knot = i;
  }
  if (first_knot == n && one_line_fits(want, tol)) return true;  // no breakpoint inside
  // reach[q][j]: a breakpoint at q, at lowest[q] + j, ends a motion within tolerance from l.
  std::vector<std::vector<char>> reach(n);
  for (std::size_t q = 0; q < n; ++q) {
    reach[q].assign(static_cast<std::size_t>(std::max(0, highest[q] - lowest[q] + 1)), 0);
  }
  // The first breakpoint inside, entered at any slope from outside (not across a knot).
  for (std::size_t q = 0; q < n && q <= first_knot; ++q) {
    for (int v = lowest[q]; v <= highest[q]; ++v) {
      double lo = -std::numeric_limits<double>::infinity(), hi = -lo;
      for (std::size_t t = q; t-- > 0 && lo <= hi;) {
        const double span = static_cast<double>(q - t);
        lo = std::max(lo, (v - want[t] - tol[t]) / span);
        hi = std::min(hi, (v - want[t] + tol[t]) / span);
      }
      reach[q][static_cast<std::size_t>(v - lowest[q])] =
          lo <= hi && std::abs(v - want[q]) <= tol[q];
    }
  }
  for (std::size_t p = 0; p < n; ++p) {
    for (int u = lowest[p]; u <= highest[p]; ++u) {
      if (!reach[p][static_cast<std::size_t>(u - lowest[p])]) continue;
      if (p == n - 1) return true;
      // Lines from (p, u): the slopes that keep every instant so far within tolerance.
      double lo = -std::numeric_limits<double>::infinity(), hi = -lo;
      for (std::size_t q = p + 1; q < n; ++q) {
        const double span = static_cast<double>(q - p);
        if (q - p >= static_cast<std::size_t>(kMinActionMs)) {
          for (int v = lowest[q]; v <= highest[q]; ++v) {
            const double slope = (v - u) / span;
            if (slope >= lo && slope <= hi && std::abs(v - want[q]) <= tol[q]) {
              reach[q][static_cast<std::size_t>(v - lowest[q])] = 1;
            }
          }
        }
        lo = std::max(lo, (want[q] - tol[q] - u) / span);
        hi = std::min(hi, (want[q] + tol[q] - u) / span);
        if (lo > hi || knot[q]) break;
        if (q == n - 1) return true;  // the line leaving the window from (p, u)
      }
    }
  }
  return false;
}

// A shortfall at `at` is proven when no motion follows the curve within tolerance over some
// window around it: the smallest of a few widths is taken, all of them short.
inline bool shortfall_proven(const Intended& c, std::int64_t at, std::int64_t end) {
  for (std::int64_t half : {30, 60, 120}) {
    if (!followable(c, std::max<std::int64_t>(0, at - half), std::min(end, at + half))) {
      return true;
    }
  }
  return false;
}

inline Timeline one_curve(const Segment& seg) {
  Timeline tl;
  tl.resize(1);
  Segment start;  // where the servo is before the curve: a short hold
  start.kind = CurveKind::Hold;
  start.start = ExactMs(0);
  start.end = seg.start;
  start.from = start.to = seg.from;
  start.tolerance = kHoldTolerance;
  tl.add(0, start);
  tl.add(0, seg);
  tl.end = ExactMs(static_cast<std::int64_t>(seg.end.round()));
  return tl;
}

}  // namespace seqc::compiler::fitting_check
