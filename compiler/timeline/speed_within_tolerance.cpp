#include "compiler/timeline/speed_within_tolerance.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>
#include <utility>
#include <vector>

namespace seqc::compiler {
namespace {

constexpr int kUniform = 1024;    // evenly spaced instants over the segment
constexpr int kPerDecade = 48;    // instants per factor of ten towards a vertical point
constexpr int kDecades = 10;      // down to 1e-10 of the segment from it
constexpr int kRefineRounds = 8;  // alternate searches for the best pair's two instants

// The largest (to[t] - from[s]) / (x[t] - x[s]) over s < t (x increasing), with its s and t.
// For each t the best s is a vertex of the lower convex hull of the points (x[s], from[s]) before
// it, where the line from (x[t], to[t]) touches that hull from below; the slope to the hull's
// vertices rises to that vertex and falls after it, so a binary search finds it. O(n log n).
std::tuple<double, std::size_t, std::size_t> steepest_rise(const std::vector<double>& x,
                                                           const std::vector<double>& from,
                                                           const std::vector<double>& to) {
  auto slope = [&](std::size_t s, std::size_t t) { return (to[t] - from[s]) / (x[t] - x[s]); };
  std::vector<std::size_t> hull;
  double best = -std::numeric_limits<double>::infinity();
  std::size_t bs = 0, bt = 0;
  for (std::size_t t = 0; t < x.size(); ++t) {
    if (!hull.empty()) {
      std::size_t lo = 0, hi = hull.size() - 1;
      while (lo < hi) {
        const std::size_t mid = (lo + hi) / 2;
        if (slope(hull[mid], t) <= slope(hull[mid + 1], t)) {
          lo = mid + 1;
        } else {
          hi = mid;
        }
      }
      if (slope(hull[lo], t) > best) {
        best = slope(hull[lo], t);
        bs = hull[lo];
        bt = t;
      }
    }
    // (x[t], from[t]) joins the lower hull: drop the vertices it leaves above the chain.
    while (hull.size() >= 2) {
      const std::size_t a = hull[hull.size() - 2], b = hull.back();
      const double cross =
          (x[b] - x[a]) * (from[t] - from[a]) - (from[b] - from[a]) * (x[t] - x[a]);
      if (cross > 0) break;
      hull.pop_back();
    }
    hull.push_back(t);
  }
  return {best, bs, bt};
}

}  // namespace

double speed_within_tolerance(const Segment& segment, double tolerance) {
  const double t0 = segment.start.value(), t1 = segment.end.value();
  const double span = t1 - t0;
  if (!(span > 0)) return 0;
  // Normalised instants: even ones, and ones packed geometrically towards the places a curve
  // can be vertical (its ends, its middle, and the steepest of the even instants).
  std::vector<double> u;
  int steepest = 0;
  double steepest_v = -1;
  for (int i = 0; i <= kUniform; ++i) {
    const double x = static_cast<double>(i) / kUniform;
    u.push_back(x);
    const double v = std::abs(segment.velocity(t0 + span * x));
    if (v > steepest_v) {
      steepest_v = v;
      steepest = i;
    }
  }
  for (const double anchor : {0.0, 0.5, 1.0, static_cast<double>(steepest) / kUniform}) {
    for (int j = 0; j <= kPerDecade * kDecades; ++j) {
      const double d = std::pow(10.0, -static_cast<double>(j) / kPerDecade);
      for (const double x : {anchor - d, anchor + d}) {
        if (x > 0 && x < 1) u.push_back(x);
      }
    }
  }
  std::sort(u.begin(), u.end());
  u.erase(std::unique(u.begin(), u.end()), u.end());
  const std::size_t n = u.size();
  // The band at each instant; the ends are pinned to the curve.
  auto band = [&](double x) {
    const double v = segment.value(t0 + span * x);
    const double tol = x <= 0 || x >= 1 ? 0.0 : tolerance;
    return std::pair<double, double>{v - tol, v + tol};
  };
  auto quotient = [&](double s, double t) {
    const auto [ls, hs] = band(s);
    const auto [lt, ht] = band(t);
    return std::max(lt - hs, ls - ht) / ((t - s) * span);
  };
  std::vector<double> low(n), high(n), minus_low(n), minus_high(n);
  for (std::size_t i = 0; i < n; ++i) {
    std::tie(low[i], high[i]) = band(u[i]);
    minus_low[i] = -low[i];
    minus_high[i] = -high[i];
  }
  double best = 0;
  std::size_t bi = 0, bj = 1;
  // Rising: (low(t) - high(s)) / (t - s); falling: the same of the band turned upside down.
  for (const auto& [from, to] : {std::pair{&high, &low}, std::pair{&minus_low, &minus_high}}) {
    const auto [q, i, j] = steepest_rise(u, *from, *to);
    if (q / span > best) {
      best = q / span;
      bi = i;
      bj = j;
    }
  }
  if (!(best > 0)) return 0;
  // The best pair lies between its neighbours on the grid: golden-section search on each
  // instant in turn (an end stays where it is: its band is a point).
  double s = u[bi], t = u[bj];
  constexpr double g = 0.6180339887498949;
  auto refine = [&](double& x, double lo, double hi, bool first) {
    for (int k = 0; k < 80; ++k) {
      const double m1 = hi - g * (hi - lo), m2 = lo + g * (hi - lo);
      const double f1 = first ? quotient(m1, t) : quotient(s, m1);
      const double f2 = first ? quotient(m2, t) : quotient(s, m2);
      if (f1 < f2) {
        lo = m1;
      } else {
        hi = m2;
      }
    }
    const double m = (lo + hi) / 2;
    const double q = first ? quotient(m, t) : quotient(s, m);
    if (q > best) {
      best = q;
      x = m;
    }
  };
  for (int round = 0; round < kRefineRounds; ++round) {
    if (bi > 0) refine(s, u[bi - 1], std::min(u[bi + 1], t), true);
    if (bj + 1 < n) refine(t, std::max(u[bj - 1], s), u[bj + 1], false);
  }
  return best * 1000.0;
}

}  // namespace seqc::compiler
