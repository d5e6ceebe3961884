// What fitting's searches share, private to compiler/fitting: a stretch of curve sampled per
// curved servo and millisecond (what each search reads: the band the controller's straight line
// may pass through at each instant, the rounded curve, the free targets, the knots), a sequence
// of actions through it (what each search returns), and the limits every search keeps (action
// lengths, the work budget). The driver (fitter.cpp) samples stretches and keeps the better of
// the searches (on_curve_search.hpp, free_search.hpp); no search reads the timeline.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace seqc::compiler::fitting {

// A search's cost is counted in slope-window updates; past kWorkBudget a stretch is cut in two
// (see fitter.cpp, Fitter::fit_range). The budget keeps any one search to some tens of
// milliseconds.
constexpr std::size_t kWorkBudget = 40'000'000;
// End values the free fit tracks per servo and boundary: one 64-bit set.
constexpr int kMaxValues = 64;
constexpr int kNoKey = std::numeric_limits<int>::max() / 2;
// Stretches up to this long (ms) are sampled every millisecond; longer ones at about
// sqrt(kCoarseWork x length / longest action) instants (a search tries each sample's actions,
// about kCoarseWork lines in all), at most kCoarseSamples (more only where the longest action
// would span fewer than four).
constexpr std::int64_t kFineMs = 10'000;
constexpr double kCoarseWork = 4e6;
constexpr std::size_t kCoarseSamples = 10'000;

// What the searches read, per curved servo and sample of a stretch: sample t lies at
// a + t * step ms. A stretch of up to kFineMs is sampled every millisecond (step 1); a longer one
// at a bounded number of evenly spaced instants, its bands narrowed by a margin that covers the
// curve between them and the rounding of its boundaries to whole milliseconds (fitter.cpp,
// Fitter::sample), so a search's cost follows its samples, not its milliseconds. The searches
// count in samples: every length they read (min_ms, max_ms, n, next_knot) is in samples.
struct Stretch {
  std::int64_t a = 0;
  std::size_t n = 0;           // its length in samples (in ms when step is 1)
  double step = 1;             // ms per sample
  std::size_t k = 0;           // curved servos
  std::vector<double> want;    // the intended position
  std::vector<double> lo, hi;  // where the straight line may be there (the model applied)
  std::vector<double> tol;
  std::vector<int> pin;                  // the on-curve target: the intended position rounded
  std::vector<int> vlo, vhi;             // free targets: whole units within tolerance and limits
  std::vector<char> pinned;              // at a knot of the servo's own: its target is `pin`
  std::vector<std::uint32_t> next_knot;  // the first knot after each ms (actions end there)
  std::vector<char> is_knot;
  std::size_t at(std::size_t i, std::size_t t) const { return i * (n + 1) + t; }
};

// A sequence of actions from a stretch's `first` ms, as end times (ms from the stretch's start)
// and each curved servo's target there.
struct Path {
  std::vector<std::size_t> ends;
  std::vector<int> values;  // ends.size() x k
  bool complete = false;    // the last end is the part's end
  bool gave_up = false;     // over the work budget: nothing found
  int key = kNoKey;         // 2 x actions, + 1 when the first action moves nothing
  std::size_t reached = 0;  // the last end (first when none)
};

// The action lengths every search keeps (in samples), and 1 / d for every length d up to the
// stretch's longest (so that the searches multiply instead of divide).
struct SearchLimits {
  std::size_t min_ms = 20;
  std::size_t max_ms = 30000;
  const std::vector<double>* inverse = nullptr;
};

inline Path gave_up() {
  Path p;
  p.gave_up = true;
  return p;
}

// The farthest boundary with a finite key, leaving at least min before `last` and before
// the next knot (first if none).
inline std::size_t farthest_reached(const Stretch& in, const std::vector<int>& best,
                                    std::size_t first, std::size_t last, std::size_t min) {
  for (std::size_t t = last - std::min(last - first, min); t > first; --t) {
    if (best[t - first] != kNoKey && (in.is_knot[t] != 0 || in.next_knot[t] - t >= min)) {
      return t;
    }
  }
  return first;
}

}  // namespace seqc::compiler::fitting
