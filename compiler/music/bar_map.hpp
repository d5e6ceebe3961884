// From the placed beats to a tempo map: the meter and the bar's first beat, the stretches of
// steady tempo (a least-squares line each), the joining of changes no one could hear, and the
// map read as one chain the way a choreography reads it. Pure functions; beat_analysis.cpp runs
// them in order.
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "compiler/music/beat_placement.hpp"
#include "compiler/music/tempo_map.hpp"

namespace seqc::music {

// Least squares t = a + b * i over the beats in [from, to) that have onsets.
struct LineFit {
  double a = 0, b = 0;
  double sse = 0;
  double sxx = 0;   // spread of the indices, for the slope's standard error
  double xbar = 0;  // mean index
  int count = 0;
};

// Prefix sums of the onsets' (index, time) pairs, so a line through any range is O(1).
class PrefixSums {
 public:
  explicit PrefixSums(const std::vector<Beat>& beats) : s_(beats.size() + 1) {
    for (std::size_t i = 0; i < beats.size(); ++i) {
      Sums add{};
      if (beats[i].has_onset) {
        const double x = double(i), y = beats[i].time_s;
        add = {1, x, y, x * x, x * y, y * y};
      }
      s_[i + 1] = s_[i] + add;
    }
  }
  LineFit fit(std::size_t from, std::size_t to) const {
    const Sums d = s_[to] - s_[from];
    LineFit f;
    f.count = static_cast<int>(d.n);
    if (d.n < 2) return f;
    const double sxx = d.xx - d.x * d.x / d.n;
    const double sxy = d.xy - d.x * d.y / d.n;
    const double syy = d.yy - d.y * d.y / d.n;
    if (sxx <= 0) return f;
    f.b = sxy / sxx;
    f.a = (d.y - f.b * d.x) / d.n;
    f.sse = std::max(0.0, syy - f.b * sxy);
    f.sxx = sxx;
    f.xbar = d.x / d.n;
    return f;
  }

 private:
  struct Sums {
    double n = 0, x = 0, y = 0, xx = 0, xy = 0, yy = 0;
    Sums operator+(const Sums& o) const {
      return {n + o.n, x + o.x, y + o.y, xx + o.xx, xy + o.xy, yy + o.yy};
    }
    Sums operator-(const Sums& o) const {
      return {n - o.n, x - o.x, y - o.y, xx - o.xx, xy - o.xy, yy - o.yy};
    }
  };
  std::vector<Sums> s_;
};

// The onsets' timing noise, from the second differences of consecutive beats (robust to tempo
// changes); at least 0.2 ms.
double jitter_sigma(const std::vector<Beat>& beats);

struct BarPhase {
  int beats = 4;
  int phase = 0;  // index (among the kept beats) of the first downbeat
};
// The meter (unless `given`) and the phase of the bar's first beat, from the beats' accents.
BarPhase bar_phase(const std::vector<Beat>& beats, std::optional<int> given);

// Stretches of steady tempo, each starting on a bar line, as beat indices (the first 0, the last
// the end); empty when no stretch has 8 beats with onsets.
std::vector<std::size_t> split_stretches(const std::vector<Beat>& beats, const BarPhase& bar,
                                         double sigma);

// Joins neighbouring stretches while one run through both stays within max(`floor`, the bars'
// own scatter) of every bar's beats.
void merge_inaudible_changes(const std::vector<Beat>& beats, const PrefixSums& sums, int per_bar,
                             double floor, std::vector<std::size_t>& bounds);

// How many decimals (0-3) of a stretch's tempo its fit supports.
int decimals_for(const LineFit& fit, double sigma);

// Each stretch's start and printed tempo chained, so the map read as a chain stays on the beats.
void make_continuous(TempoMap& map, const std::vector<std::size_t>& bounds, const PrefixSums& sums);

// Beat `k` of the printed chain (0 is bar 1 beat 1; negative counts back at the first tempo).
double chain_time(const TempoMap& map, long k);

}  // namespace seqc::music
