#include <algorithm>
#include <bit>
#include <cstdint>
#include <tuple>
#include <utility>
#include <vector>

#include "compiler/fitting/free_search.hpp"
#include "compiler/fitting/free_targets.hpp"

namespace seqc::compiler::fitting {

// The key of the fit along the rounded curve taken greedily, each action to the farthest
// boundary its line reaches that leaves room for the next (kNoKey where that walk gets stuck):
// a fit the exact search finds too (the same windows, the same test of a target). It costs
// one pass over the stretch.
int greedy_on_curve_key(const Stretch& in, const SearchLimits& lim, std::size_t first,
                        std::size_t last) {
  const std::size_t min = lim.min_ms, max = lim.max_ms;
  const int* const pin = in.pin.data() + in.at(0, 0);
  const double* const band_lo = in.lo.data() + in.at(0, 0);
  const double* const band_hi = in.hi.data() + in.at(0, 0);
  const double* const inv = lim.inverse->data();
  int key = 0;
  std::size_t s = first;
  while (s < last) {
    const std::size_t stop = std::min({last, s + max, std::size_t{in.next_knot[s]}});
    const double u = pin[s];
    double lo = -1e300, hi = 1e300;
    std::size_t to = s;
    for (std::size_t e = s + 1; e <= stop; ++e) {
      const bool room = e == last || in.is_knot[e] != 0 || in.next_knot[e] - e >= min;
      if (e - s >= min && room &&
          reachable(pin[s], lo, hi, static_cast<double>(e - s), pin[e], pin[e]) != 0) {
        to = e;
      }
      const double r = inv[e - s];
      lo = std::max(lo, (band_lo[e] - u) * r);
      hi = std::min(hi, (band_hi[e] - u) * r);
      if (lo > hi) break;
    }
    if (to == s) return kNoKey;
    key += 2 + (s == first && pin[to] == pin[first] ? 1 : 0);
    s = to;
  }
  return key;
}

// The free fit for one curved servo, exact: the fewest actions to reach each whole unit v at
// each ms t (within tolerance, inside the limits), from every reachable (s, u) along every
// line that stays within the band at every millisecond between; among as few actions, one with
// every target on the rounded curve where there is one (so that where free end points save
// nothing, the fit is an on-curve one). Only fits with a key below `bound` are looked for.
Path free_single_search(const Stretch& in, const SearchLimits& lim, std::size_t first,
                        std::size_t last, int bound, std::size_t& work) {
  const std::size_t min = lim.min_ms, max = lim.max_ms;
  const std::size_t len = last - first + 1;
  // The start is pinned: index 0 of a band holding that value alone.
  std::vector<int> low(len), high(len);
  for (std::size_t t = first; t <= last; ++t) {
    std::tie(low[t - first], high[t - first]) = free_band(in, 0, t, last);
  }
  low[0] = high[0] = in.pin[in.at(0, first)];
  // The tables hold as many values per ms as the widest band (2 x tolerance + 1 at most, and
  // never more than kMaxValues), so that a search at a small tolerance stays in the cache.
  std::size_t W = 1;
  for (std::size_t t = 0; t < len; ++t) {
    W = std::max<std::size_t>(W, static_cast<std::size_t>(std::max(high[t] - low[t] + 1, 1)));
  }
  // A state's cost, compared as one number: its key, then whether a target on the way there is
  // off the rounded curve (the low bit, or-ed along the way).
  auto cost = [](int key, int off) {
    return static_cast<std::int64_t>(key) << 32 | static_cast<std::int64_t>(off);
  };
  const std::int64_t none = cost(kNoKey, 0);
  std::vector<std::int64_t> costs(len * W, none);
  std::vector<std::uint32_t> from_t(len * W);
  std::vector<std::uint8_t> from_v(len * W);
  std::vector<int> best_at(len, kNoKey);  // the smallest key at each t
  // At each t, the largest cost of a value off the rounded curve and the cost of the value on
  // it (the smallest cost when the band does not hold it): a start whose candidates would cost
  // no less than these is not tried there.
  std::vector<std::int64_t> worst_off(len, none), on_pin(len, none);
  // Raw pointers held in locals: the byte stores into from_v may alias anything, and would
  // otherwise make the compiler load every vector's data pointer again on each candidate.
  std::int64_t* const cost_at = costs.data();
  std::uint32_t* const from_t_at = from_t.data();
  std::uint8_t* const from_v_at = from_v.data();
  int* const best_p = best_at.data();
  std::int64_t* const worst_off_p = worst_off.data();
  std::int64_t* const on_pin_p = on_pin.data();
  const int* const low_p = low.data();
  const int* const high_p = high.data();
  const int* const pin = in.pin.data() + in.at(0, 0);
  const double* const band_lo = in.lo.data() + in.at(0, 0);
  const double* const band_hi = in.hi.data() + in.at(0, 0);
  const double* const inv = lim.inverse->data();
  const std::uint32_t* const next_knot = in.next_knot.data();
  auto K = [&](std::size_t t, int j) {
    return static_cast<int>(cost_at[(t - first) * W + static_cast<std::size_t>(j)] >> 32);
  };
  cost_at[0] = cost(0, 0);
  best_p[0] = 0;
  int u[kMaxValues], uj[kMaxValues];
  std::int64_t uc[kMaxValues];
  // The work, counted in a local (the caller's counter is a reference the stores below might
  // alias) against what is left of the budget.
  std::size_t spent = 0;
  const std::size_t budget = kWorkBudget - std::min(work, kWorkBudget);
  for (std::size_t s = first; s < last; ++s) {
    const int ls = low_p[s - first], hs = high_p[s - first];
    // A start can lead to a better fit only with an action to spare below the bound, and below
    // the best fit found so far with an action to spare or as many (then one on the curve).
    const int k_last = K(last, 0);
    int n = 0;
    for (int v = ls; v <= hs; ++v) {
      const std::int64_t c = cost_at[(s - first) * W + static_cast<std::size_t>(v - ls)];
      const int k = static_cast<int>(c >> 32);
      if (k == kNoKey || k + 2 >= bound || k + 2 > k_last) continue;
      u[n] = v;
      uj[n] = v - ls;
      uc[n] = c + cost(2, 0);  // an action more
      ++n;
    }
    const std::size_t stop = std::min({last, s + max, std::size_t{next_knot[s]}});
    // One start at a time, its slope window held in registers. Starts of the same s improve
    // an end in the same order as they would end by end (the first of equal costs is kept).
    for (int o = 0; o < n; ++o) {
      const double d = u[o];
      const std::int64_t c0 = uc[o];
      double lo = -1e300, hi = 1e300;
      for (std::size_t e = s + 1; e <= stop; ++e) {
        if (++spent > budget) {
          work += spent;
          return gave_up();
        }
        const std::size_t at = e - first;
        const int le = low_p[at], he = high_p[at];
        // Most candidates arrive where every value already costs as little (brought up to
        // date on each improvement).
        if (e - s >= min && le <= he && ((c0 | 1) < worst_off_p[at] || c0 < on_pin_p[at])) {
          std::uint64_t bits = reachable(u[o], lo, hi, static_cast<double>(e - s), le, he);
          bool improved = false;
          while (bits != 0) {
            const int j = std::countr_zero(bits);
            bits &= bits - 1;
            const int v = le + j;
            // A first action that moves nothing costs a half action more.
            const std::int64_t c =
                (c0 + (s == first && v == u[o] ? cost(1, 0) : 0)) | (v != pin[e] ? 1 : 0);
            const std::size_t x = at * W + static_cast<std::size_t>(j);
            if (c < cost_at[x]) {
              cost_at[x] = c;
              from_t_at[x] = static_cast<std::uint32_t>(s);
              from_v_at[x] = static_cast<std::uint8_t>(uj[o]);
              best_p[at] = std::min(best_p[at], static_cast<int>(c >> 32));
              improved = true;
            }
          }
          if (improved) {
            std::int64_t worst = 0, at_pin = 0;
            for (int j = 0; j <= he - le; ++j) {
              const std::int64_t c = cost_at[at * W + static_cast<std::size_t>(j)];
              if (le + j == pin[e]) {
                at_pin = c;
              } else {
                worst = std::max(worst, c);
              }
            }
            worst_off_p[at] = worst;
            on_pin_p[at] = at_pin;
          }
        }
        const double r = inv[e - s];
        lo = std::max(lo, (band_lo[e] - d) * r);
        hi = std::min(hi, (band_hi[e] - d) * r);
        if (lo > hi) break;
      }
    }
  }
  work += spent;
  Path path;
  std::size_t t = last;
  int j = 0;
  if (K(last, 0) == kNoKey) {
    if (bound != kNoKey) return path;  // nothing better than the on-curve fit
    t = farthest_reached(in, best_at, first, last, min);
    // At the farthest boundary, the value with the fewest actions, nearest the curve.
    for (int c = 0; c <= high[t - first] - low[t - first]; ++c) {
      const double w = in.want[in.at(0, t)];
      if (K(t, c) < K(t, j) || (K(t, c) == K(t, j) && std::abs(low[t - first] + c - w) <
                                                          std::abs(low[t - first] + j - w))) {
        j = c;
      }
    }
  }
  path.complete = t == last;
  path.reached = t;
  path.key = t == first ? 0 : K(t, j);
  if (!path.complete) path.key += 4 * static_cast<int>(last - t);
  std::vector<std::pair<std::size_t, int>> back;
  while (t > first) {
    back.push_back({t, low[t - first] + j});
    const std::size_t i = (t - first) * W + static_cast<std::size_t>(j);
    t = from_t[i];
    j = from_v[i];
  }
  std::reverse(back.begin(), back.end());
  for (const auto& [end, value] : back) {
    path.ends.push_back(end);
    path.values.push_back(value);
  }
  return path;
}

}  // namespace seqc::compiler::fitting
