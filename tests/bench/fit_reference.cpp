#include "tests/bench/fit_reference.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <vector>

namespace seqc::compiler::fit_reference {

// The exact minimum number of actions for one curve over [0, D] with free end points: the
// fewest actions reaching each (t, v), v a whole unit within tol of the curve at t, from the
// rounded curve at 0 to the rounded curve at D, each 20 ms to 30 s, each straight line within
// tol at every millisecond. For a fixed start (a, u) the line to (b, v) fits exactly when its
// slope lies in the intersection of the windows [(c(t) - tol - u) / (t - a), (c(t) + tol - u) /
// (t - a)] of the instants before b, so the windows are intersected as b grows. Every state and
// every pair is decided; 1 << 30 when none reaches D.
int free_minimum(const Piece& p, int duration, double tol) {
  std::vector<double> c(duration + 1);
  for (int t = 0; t <= duration; ++t) c[t] = p.at(t);
  const double eps = 1e-9;
  auto lowest = [&](int t) { return static_cast<int>(std::ceil(c[t] - tol - eps)); };
  auto highest = [&](int t) { return static_cast<int>(std::floor(c[t] + tol + eps)); };
  std::vector<std::vector<int>> best(duration + 1);
  for (int t = 0; t <= duration; ++t) {
    best[t].assign(static_cast<std::size_t>(std::max(0, highest(t) - lowest(t) + 1)), 1 << 30);
  }
  const int start = static_cast<int>(std::lround(c[0])),
            end = static_cast<int>(std::lround(c[duration]));
  best[0].assign(1, 0);
  int best_end = 1 << 30;
  auto low_of = [&](int t) { return t == 0 ? start : lowest(t); };
  for (int a = 0; a < duration; ++a) {
    for (std::size_t j = 0; j < best[a].size(); ++j) {
      if (best[a][j] >= (1 << 30)) continue;
      const double u = low_of(a) + static_cast<int>(j);
      double lo = -1e300, hi = 1e300;
      for (int b = a + 1; b <= std::min(duration, a + 30000); ++b) {
        const double span = b - a;
        if (b - a >= 20 && b == duration) {
          const double slope = (end - u) / span;
          if (slope >= lo - 1e-12 && slope <= hi + 1e-12)
            best_end = std::min(best_end, best[a][j] + 1);
        } else if (b - a >= 20) {
          for (int v = lowest(b); v <= highest(b); ++v) {
            const double slope = (v - u) / span;
            if (slope < lo - 1e-12 || slope > hi + 1e-12) continue;
            int& cell = best[b][static_cast<std::size_t>(v - lowest(b))];
            cell = std::min(cell, best[a][j] + 1);
          }
        }
        lo = std::max(lo, (c[b] - tol - eps - u) / span);
        hi = std::min(hi, (c[b] + tol + eps - u) / span);
        if (lo > hi) break;
      }
    }
  }
  return best_end;
}

// The knots of a set of tracks as the fitter's documented rule makes them: every piece's start
// and end, 0 and the end, a knot closer than 20 ms to the one kept before it dropped (the end
// kept instead of the one before it).
std::vector<int> knots_of(const std::vector<Track>& tracks, int end_ms) {
  std::vector<int> all = {0, end_ms};
  for (const Track& tr : tracks) {
    for (const Piece& p : tr.pieces) {
      all.push_back(static_cast<int>(p.t0));
      all.push_back(static_cast<int>(p.t1));
    }
  }
  std::sort(all.begin(), all.end());
  all.erase(std::unique(all.begin(), all.end()), all.end());
  std::vector<int> kept;
  for (int k : all) {
    if (k < 0 || k > end_ms) continue;
    if (kept.empty() || k - kept.back() >= 20) {
      kept.push_back(k);
    } else if (k == end_ms && kept.size() > 1) {
      kept.back() = end_ms;
    }
  }
  return kept;
}

// The fewest actions one servo needs over [a, b] on its own: the windowed dynamic program of
// free_minimum() over every (ms, whole unit) state, starting from any whole unit within tol of
// the curve at a (only the rounded curve when `pin_a`) and ending at any within tol at b (only
// the rounded curve when `pin_b`). 1 << 30 when none reaches b.
int interval_minimum(const Track& tr, int a, int b, double tol, bool pin_a, bool pin_b) {
  const int n = b - a;
  std::vector<double> c(static_cast<std::size_t>(n + 1));
  for (int t = 0; t <= n; ++t) c[static_cast<std::size_t>(t)] = tr.at(a + t);
  const double eps = 1e-9;
  auto lowest = [&](int t) {
    const double w = c[static_cast<std::size_t>(t)];
    if ((t == 0 && pin_a) || (t == n && pin_b)) return static_cast<int>(std::lround(w));
    return static_cast<int>(std::ceil(w - tol - eps));
  };
  auto highest = [&](int t) {
    const double w = c[static_cast<std::size_t>(t)];
    if ((t == 0 && pin_a) || (t == n && pin_b)) return static_cast<int>(std::lround(w));
    return static_cast<int>(std::floor(w + tol + eps));
  };
  std::vector<std::vector<int>> best(static_cast<std::size_t>(n + 1));
  for (int t = 0; t <= n; ++t) {
    best[static_cast<std::size_t>(t)].assign(
        static_cast<std::size_t>(std::max(0, highest(t) - lowest(t) + 1)), t == 0 ? 0 : 1 << 30);
  }
  for (int s = 0; s < n; ++s) {
    const std::vector<int>& from = best[static_cast<std::size_t>(s)];
    for (std::size_t j = 0; j < from.size(); ++j) {
      if (from[j] >= (1 << 30)) continue;
      const double u = lowest(s) + static_cast<int>(j);
      double lo = -1e300, hi = 1e300;
      for (int e = s + 1; e <= std::min(n, s + 30000); ++e) {
        const double span = e - s;
        if (e - s >= 20) {
          for (int v = lowest(e); v <= highest(e); ++v) {
            const double slope = (v - u) / span;
            if (slope < lo - 1e-12 || slope > hi + 1e-12) continue;
            int& cell = best[static_cast<std::size_t>(e)][static_cast<std::size_t>(v - lowest(e))];
            cell = std::min(cell, from[j] + 1);
          }
        }
        const double w = c[static_cast<std::size_t>(e)];
        lo = std::max(lo, (w - tol - eps - u) / span);
        hi = std::min(hi, (w + tol + eps - u) / span);
        if (lo > hi) break;
      }
    }
  }
  const std::vector<int>& end = best[static_cast<std::size_t>(n)];
  return end.empty() ? 1 << 30 : *std::min_element(end.begin(), end.end());
}

// A floor under any fit that keeps the knot rule (every knot an action boundary for every
// servo, a servo's target pinned to its rounded curve at its own boundaries): per interval
// between knots, the most actions any one servo needs there on its own (at least one). The
// servos' shared boundaries inside an interval and the value each carries over a knot are
// relaxed, so the true minimum is at least this. Intervals no single action can cross within
// tolerance (a shortfall) count one.
long knot_floor(const std::vector<Track>& tracks, int end_ms, double tol) {
  const std::vector<int> knots = knots_of(tracks, end_ms);
  auto own = [&](const Track& tr, int k) {
    for (const Piece& p : tr.pieces) {
      if (static_cast<int>(p.t0) == k || static_cast<int>(p.t1) == k) return true;
    }
    return false;
  };
  long total = 0;
  for (std::size_t j = 0; j + 1 < knots.size(); ++j) {
    int most = 1;
    for (const Track& tr : tracks) {
      const int m = interval_minimum(tr, knots[j], knots[j + 1], tol, own(tr, knots[j]),
                                     own(tr, knots[j + 1]));
      if (m < (1 << 30)) most = std::max(most, m);
    }
    total += most;
  }
  return total;
}

// The exact fewest actions for two servos under the knot rule, where every action stays within
// tolerance (-1 when some interval cannot be crossed so: a shortfall, where "fewest" has no
// meaning): dynamic programming over every (ms, whole unit of servo 0, whole unit of servo 1)
// state, each action a pair of straight lines from one state to a later one, at least 20 ms
// long, not crossing a knot, both within tolerance of their tracks at every millisecond. The
// same windows as interval_minimum(), per servo; the pair's reachable targets are the product
// of the two servos' sets.
long exact_two_servo_minimum(const std::vector<Track>& tracks, int end_ms, double tol) {
  const std::vector<int> knots = knots_of(tracks, end_ms);
  const double eps = 1e-9;
  std::vector<char> is_knot(static_cast<std::size_t>(end_ms) + 1, 0);
  for (int k : knots) is_knot[static_cast<std::size_t>(k)] = 1;
  std::vector<int> next_knot(static_cast<std::size_t>(end_ms) + 1, end_ms);
  for (int t = end_ms - 1; t >= 0; --t) {
    next_knot[static_cast<std::size_t>(t)] = is_knot[static_cast<std::size_t>(t) + 1] != 0
                                                 ? t + 1
                                                 : next_knot[static_cast<std::size_t>(t) + 1];
  }
  auto own = [&](const Track& tr, int k) {
    if (k == 0) return true;
    for (const Piece& p : tr.pieces) {
      if (static_cast<int>(p.t0) == k || static_cast<int>(p.t1) == k) return true;
    }
    return false;
  };
  // Each servo's curve and its targets [low, high] at every ms.
  std::vector<double> c[2];
  std::vector<int> low[2], high[2];
  for (int i = 0; i < 2; ++i) {
    for (int t = 0; t <= end_ms; ++t) {
      const double w = tracks[static_cast<std::size_t>(i)].at(t);
      c[i].push_back(w);
      if (is_knot[static_cast<std::size_t>(t)] != 0 &&
          own(tracks[static_cast<std::size_t>(i)], t)) {
        low[i].push_back(static_cast<int>(std::lround(w)));
        high[i].push_back(static_cast<int>(std::lround(w)));
      } else {
        low[i].push_back(static_cast<int>(std::ceil(w - tol - eps)));
        high[i].push_back(static_cast<int>(std::floor(w + tol + eps)));
      }
    }
  }
  auto width = [&](int i, int t) {
    return std::max(0,
                    high[i][static_cast<std::size_t>(t)] - low[i][static_cast<std::size_t>(t)] + 1);
  };
  constexpr int kFar = 1 << 30;
  std::vector<std::vector<int>> best(static_cast<std::size_t>(end_ms) + 1);
  for (int t = 0; t <= end_ms; ++t) {
    best[static_cast<std::size_t>(t)].assign(static_cast<std::size_t>(width(0, t) * width(1, t)),
                                             kFar);
  }
  best[0][0] = 0;
  // reach[i][u][e - s]: servo i's targets (bits from low at e) a line from its u-th value at s
  // reaches within tolerance; 0 once the window has closed.
  std::vector<std::vector<std::uint64_t>> reach[2];
  std::vector<int> open_until[2];  // per start value: the last end its window reaches
  for (int s = 0; s < end_ms; ++s) {
    const std::vector<int>& here = best[static_cast<std::size_t>(s)];
    if (std::all_of(here.begin(), here.end(), [](int d) { return d >= kFar; })) continue;
    const int stop = next_knot[static_cast<std::size_t>(s)];
    for (int i = 0; i < 2; ++i) {
      reach[i].assign(static_cast<std::size_t>(width(i, s)),
                      std::vector<std::uint64_t>(static_cast<std::size_t>(stop - s) + 1, 0));
      open_until[i].assign(static_cast<std::size_t>(width(i, s)), stop);
      for (int j = 0; j < width(i, s); ++j) {
        const double u = low[i][static_cast<std::size_t>(s)] + j;
        double lo = -1e300, hi = 1e300;
        for (int e = s + 1; e <= stop; ++e) {
          const double span = e - s;
          std::uint64_t bits = 0;
          for (int v = low[i][static_cast<std::size_t>(e)];
               v <= high[i][static_cast<std::size_t>(e)]; ++v) {
            const double slope = (v - u) / span;
            if (slope >= lo - 1e-12 && slope <= hi + 1e-12) {
              bits |= std::uint64_t{1} << (v - low[i][static_cast<std::size_t>(e)]);
            }
          }
          reach[i][static_cast<std::size_t>(j)][static_cast<std::size_t>(e - s)] = bits;
          const double w = c[i][static_cast<std::size_t>(e)];
          lo = std::max(lo, (w - tol - eps - u) / span);
          hi = std::min(hi, (w + tol + eps - u) / span);
          if (lo > hi) {
            open_until[i][static_cast<std::size_t>(j)] = e;
            break;
          }
        }
      }
    }
    const int w1s = width(1, s);
    for (std::size_t x = 0; x < here.size(); ++x) {
      const int d = here[x];
      if (d >= kFar) continue;
      const std::size_t j0s = x / static_cast<std::size_t>(w1s);
      const std::size_t j1s = x % static_cast<std::size_t>(w1s);
      const auto& r0 = reach[0][j0s];
      const auto& r1 = reach[1][j1s];
      const int until = std::min(open_until[0][j0s], open_until[1][j1s]);
      for (int e = s + 20; e <= until; ++e) {
        const std::uint64_t a0 = r0[static_cast<std::size_t>(e - s)];
        const std::uint64_t a1 = r1[static_cast<std::size_t>(e - s)];
        if (a0 == 0 || a1 == 0) continue;
        std::vector<int>& there = best[static_cast<std::size_t>(e)];
        const int w1e = width(1, e);
        for (std::uint64_t b0 = a0; b0 != 0; b0 &= b0 - 1) {
          const int j0 = std::countr_zero(b0);
          for (std::uint64_t b1 = a1; b1 != 0; b1 &= b1 - 1) {
            int& cell = there[static_cast<std::size_t>(j0 * w1e + std::countr_zero(b1))];
            cell = std::min(cell, d + 1);
          }
        }
      }
    }
  }
  const std::vector<int>& end = best[static_cast<std::size_t>(end_ms)];
  const int m = end.empty() ? kFar : *std::min_element(end.begin(), end.end());
  return m >= kFar ? -1 : m;
}

}  // namespace seqc::compiler::fit_reference
