#include <algorithm>
#include <bit>
#include <cstdint>
#include <tuple>
#include <utility>
#include <vector>

#include "compiler/fitting/free_search.hpp"
#include "compiler/fitting/free_targets.hpp"

namespace seqc::compiler::fitting {

// The free fit for one curved servo, exact: the fewest actions to reach each whole unit v at
// each ms t (within tolerance, inside the limits), from every reachable (s, u) along every
// line that stays within the band at every millisecond between. Only fits with a key below
// `bound` (the on-curve fit's) are looked for.
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
  std::vector<int> key(len * W, kNoKey);
  std::vector<std::uint32_t> from_t(len * W);
  std::vector<std::uint8_t> from_v(len * W);
  auto K = [&](std::size_t t, int j) -> int& {
    return key[(t - first) * W + static_cast<std::size_t>(j)];
  };
  K(first, 0) = 0;
  std::vector<int> best_at(len, kNoKey);   // the smallest key at each t
  std::vector<int> worst_at(len, kNoKey);  // the largest
  best_at[0] = 0;
  const std::vector<double>& inv = *lim.inverse;
  int u[kMaxValues], uj[kMaxValues], uk[kMaxValues];
  double lo[kMaxValues], hi[kMaxValues];
  for (std::size_t s = first; s < last; ++s) {
    const int ls = low[s - first], hs = high[s - first];
    const int limit = std::min(bound, K(last, 0));
    int n = 0;
    for (int v = ls; v <= hs; ++v) {
      const int k = K(s, v - ls);
      if (k == kNoKey || k + 2 >= limit) continue;
      u[n] = v;
      uj[n] = v - ls;
      uk[n] = k;
      lo[n] = -1e300;
      hi[n] = 1e300;
      ++n;
    }
    if (n == 0) continue;
    int ks = uk[0];  // the smallest key among the starts
    for (int o = 1; o < n; ++o) ks = std::min(ks, uk[o]);
    const std::size_t stop = std::min({last, s + max, std::size_t{in.next_knot[s]}});
    for (std::size_t e = s + 1; e <= stop; ++e) {
      work += static_cast<std::size_t>(n);
      if (work > kWorkBudget) return gave_up();
      const double span = static_cast<double>(e - s), r = inv[e - s];
      const int le = low[e - first], he = high[e - first];
      // Most candidates arrive where every value already has as few actions (worst_at: the
      // largest key at e, brought up to date once per end).
      if (e - s >= min && le <= he && ks + 2 < worst_at[e - first]) {
        bool improved = false;
        for (int o = 0; o < n; ++o) {
          if (uk[o] + 2 >= worst_at[e - first]) continue;
          std::uint64_t bits = reachable(u[o], lo[o], hi[o], span, le, he);
          while (bits != 0) {
            const int j = std::countr_zero(bits);
            bits &= bits - 1;
            const int k = uk[o] + 2 + (s == first && le + j == u[o] ? 1 : 0);
            if (k < K(e, j)) {
              K(e, j) = k;
              from_t[(e - first) * W + static_cast<std::size_t>(j)] = static_cast<std::uint32_t>(s);
              from_v[(e - first) * W + static_cast<std::size_t>(j)] =
                  static_cast<std::uint8_t>(uj[o]);
              best_at[e - first] = std::min(best_at[e - first], k);
              improved = true;
            }
          }
        }
        if (improved) {
          int worst = 0;
          for (int c = 0; c <= he - le; ++c) worst = std::max(worst, K(e, c));
          worst_at[e - first] = worst;
        }
      }
      const std::size_t x = in.at(0, e);
      const double bl = in.lo[x], bh = in.hi[x];
      bool open = false;
      for (int o = 0; o < n; ++o) {
        lo[o] = std::max(lo[o], (bl - u[o]) * r);
        hi[o] = std::min(hi[o], (bh - u[o]) * r);
        open = open || lo[o] <= hi[o];
      }
      if (!open) break;
    }
  }
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
