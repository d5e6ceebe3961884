#include "compiler/fitting/on_curve_search.hpp"

#include <algorithm>
#include <vector>

namespace seqc::compiler::fitting {

// The on-curve fit: the fewest actions from `first` to `last` whose targets are the rounded
// curve, keeping every servo within tolerance at every millisecond. Dynamic programming over
// boundaries on the 1 ms grid: from each reachable start, lines to later ends are tried while
// the slope windows stay open (for a fixed start, the line to e is within the band at instant
// t exactly when its slope lies in a window set by t; intersecting the windows of all
// instants so far makes each candidate O(servos)). When no sequence reaches `last`, the
// actions reach the farthest boundary any of them reaches (leaving at least min before it),
// from which none goes on: the shortfall is there.
Path on_curve_search(const Stretch& in, const SearchLimits& lim, std::size_t first,
                     std::size_t last, std::size_t& work) {
  const std::size_t k = in.k;
  const std::size_t min = lim.min_ms, max = lim.max_ms;
  std::vector<int> best(last - first + 1, kNoKey);
  std::vector<std::size_t> from(last - first + 1);
  auto B = [&](std::size_t t) -> int& { return best[t - first]; };
  B(first) = 0;
  std::vector<double> lo(k), hi(k);
  for (std::size_t s = first; s < last; ++s) {
    if (B(s) == kNoKey || B(s) + 2 >= B(last)) continue;
    std::fill(lo.begin(), lo.end(), -1e300);
    std::fill(hi.begin(), hi.end(), 1e300);
    const std::size_t stop = std::min({last, s + max, std::size_t{in.next_knot[s]}});
    for (std::size_t e = s + 1; e <= stop; ++e) {
      work += k;
      if (work > kWorkBudget) return gave_up();
      const double span = static_cast<double>(e - s);
      if (e - s >= min && B(s) + 2 < B(e)) {
        bool fits = true, moves = false;
        for (std::size_t i = 0; i < k && fits; ++i) {
          const int p0 = in.pin[in.at(i, s)], p1 = in.pin[in.at(i, e)];
          const double slope = (p1 - p0) / span;
          fits = slope >= lo[i] - 1e-12 && slope <= hi[i] + 1e-12;
          moves = moves || p1 != p0;
        }
        const int key = B(s) + 2 + (s == first && !moves ? 1 : 0);
        if (fits && key < B(e)) {
          B(e) = key;
          from[e - first] = s;
        }
      }
      bool open = true;
      for (std::size_t i = 0; i < k; ++i) {
        const double p0 = in.pin[in.at(i, s)];
        const std::size_t x = in.at(i, e);
        lo[i] = std::max(lo[i], (in.lo[x] - p0) / span);
        hi[i] = std::min(hi[i], (in.hi[x] - p0) / span);
        open = open && lo[i] <= hi[i];
      }
      if (!open) break;
    }
  }
  std::size_t reached = last;
  if (B(last) == kNoKey) reached = farthest_reached(in, best, first, last, min);
  Path path;
  path.complete = reached == last;
  path.reached = reached;
  path.key = B(reached) + (path.complete ? 0 : 4 * static_cast<int>(last - reached));
  for (std::size_t t = reached; t > first; t = from[t - first]) path.ends.push_back(t);
  std::reverse(path.ends.begin(), path.ends.end());
  for (std::size_t t : path.ends) {
    for (std::size_t i = 0; i < k; ++i) path.values.push_back(in.pin[in.at(i, t)]);
  }
  return path;
}

}  // namespace seqc::compiler::fitting
