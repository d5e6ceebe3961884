// What the two free-end-point searches share, private to compiler/fitting: a servo's free
// targets at a millisecond, and the whole units a line from a start value reaches inside its
// slope window there (free_single_search.cpp, free_joint_search.cpp).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <utility>

#include "compiler/fitting/stretch.hpp"

namespace seqc::compiler::fitting {

// The free targets of servo i at ms t of the stretch as [low, high] (the pinned value at the
// part's end).
inline std::pair<int, int> free_band(const Stretch& in, std::size_t i, std::size_t t,
                                     std::size_t last) {
  const std::size_t x = in.at(i, t);
  if (t == last || in.pinned[x] != 0) return {in.pin[x], in.pin[x]};
  return {in.vlo[x], in.vhi[x]};
}

// The set (bits from `low`) of whole units v in [low, high] with u + lo * span <= v <=
// u + hi * span: the targets a line from u reaches inside its slope window.
inline std::uint64_t reachable(int u, double lo, double hi, double span, int low, int high) {
  // Clamped to the band first, so that the whole-unit bounds fit an int (and are found
  // without a library call: this runs for every start at every candidate end). The slack
  // is at least the on-curve search's (1e-12 on the slope), so that every on-curve line is
  // found here too.
  const double slack = 1e-9 + 1e-12 * span;
  const double a = std::clamp(u + lo * span - slack, low - 1.0, high + 1.0);
  const double b = std::clamp(u + hi * span + slack, low - 1.0, high + 1.0);
  int from = static_cast<int>(a), to = static_cast<int>(b);
  from += from < a ? 1 : 0;  // ceil
  to -= to > b ? 1 : 0;      // floor
  from = std::max(from, low);
  to = std::min(to, high);
  if (from > to) return 0;
  const int width = to - from + 1;
  const std::uint64_t bits = width >= 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << width) - 1;
  return bits << (from - low);
}

}  // namespace seqc::compiler::fitting
