#include "compiler/music/bar_map.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <limits>
#include <numeric>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

namespace seqc::music {
namespace {

// How far one stretch made of [from, mid) and [mid, to) would stray from their beats, bar by
// bar (each bar's onsets averaged), read as the map reads it: a straight run from where the
// first one's line starts to where the second one's line ends. The longest run of bars beyond
// `audible`, and the largest bar's offset.
struct Stray {
  int run = 0;
  double worst = 0;
};
Stray stray_if_joined(const std::vector<Beat>& beats, const PrefixSums& sums, std::size_t from,
                      std::size_t mid, std::size_t to, int per_bar, double audible) {
  const LineFit first = sums.fit(from, mid);
  const LineFit second = sums.fit(mid, to);
  if (first.count < 2 || second.count < 2) return {std::numeric_limits<int>::max(), 0};
  const double start = first.a + first.b * double(from);
  const double end = second.a + second.b * double(to);
  const double slope = (end - start) / double(to - from);
  Stray stray;
  int run = 0;
  for (std::size_t bar = from; bar < to; bar += static_cast<std::size_t>(per_bar)) {
    double sum = 0;
    int n = 0;
    for (std::size_t i = bar; i < std::min(to, bar + static_cast<std::size_t>(per_bar)); ++i) {
      if (!beats[i].has_onset) continue;
      sum += beats[i].time_s - (start + slope * double(i - from));
      ++n;
    }
    if (n == 0) continue;
    const double offset = std::abs(sum / n);
    stray.worst = std::max(stray.worst, offset);
    run = offset > audible ? run + 1 : 0;
    stray.run = std::max(stray.run, run);
  }
  return stray;
}

// Each bar's offset from its own stretch's line (the bar's onsets averaged), for every bar.
std::vector<double> bar_offsets(const std::vector<Beat>& beats, const PrefixSums& sums,
                                const std::vector<std::size_t>& bounds, int per_bar) {
  std::vector<double> out;
  for (std::size_t s = 0; s + 1 < bounds.size(); ++s) {
    const LineFit f = sums.fit(bounds[s], bounds[s + 1]);
    for (std::size_t start = bounds[s]; start < bounds[s + 1];
         start += static_cast<std::size_t>(per_bar)) {
      double sum = 0;
      int n = 0;
      for (std::size_t i = start;
           i < std::min(bounds[s + 1], start + static_cast<std::size_t>(per_bar)); ++i) {
        if (!beats[i].has_onset) continue;
        sum += beats[i].time_s - (f.a + f.b * double(i));
        ++n;
      }
      if (n > 0) out.push_back(sum / n);
    }
  }
  return out;
}

}  // namespace

// The timing noise of the onsets: second differences of evenly spaced beats are three beats'
// jitter (variance 6 sigma^2), and their median absolute deviation ignores tempo changes.
double jitter_sigma(const std::vector<Beat>& beats) {
  std::vector<double> d2;
  for (std::size_t i = 1; i + 1 < beats.size(); ++i) {
    if (beats[i - 1].has_onset && beats[i].has_onset && beats[i + 1].has_onset) {
      d2.push_back(std::abs(beats[i + 1].time_s - 2 * beats[i].time_s + beats[i - 1].time_s));
    }
  }
  if (d2.empty()) return 1e-3;
  std::nth_element(d2.begin(), d2.begin() + long(d2.size() / 2), d2.end());
  const double sigma = 1.4826 * d2[d2.size() / 2] / std::sqrt(6.0);
  return std::max(sigma, 2e-4);
}

// Which beat of the bar is 1, and how many beats a bar has (unless given): per phase of the
// bar, the mean accent of its beats; the meter whose strongest phase stands out most from its
// others wins, and that phase is the downbeat. Two beats to the bar must stand out a fifth more
// than four, and six a fifth more than three: a bar of four whose third beat is nearly as
// strong as its first scores well as two, and two bars of three as one of six.
BarPhase bar_phase(const std::vector<Beat>& beats, std::optional<int> given) {
  BarPhase best;
  double best_contrast = -std::numeric_limits<double>::infinity();
  std::vector<int> meters = given ? std::vector<int>{*given} : std::vector<int>{4, 3, 2, 6};
  for (int m : meters) {
    std::vector<double> sum(static_cast<std::size_t>(m), 0.0);
    std::vector<int> count(static_cast<std::size_t>(m), 0);
    for (std::size_t i = 0; i < beats.size(); ++i) {
      sum[i % static_cast<std::size_t>(m)] += beats[i].accent;
      ++count[i % static_cast<std::size_t>(m)];
    }
    double total = 0;
    int top = 0;
    for (int p = 0; p < m; ++p) {
      const auto u = static_cast<std::size_t>(p);
      sum[u] = count[u] > 0 ? sum[u] / count[u] : 0;
      total += sum[u];
      if (sum[u] > sum[static_cast<std::size_t>(top)]) top = p;
    }
    const double others = (total - sum[static_cast<std::size_t>(top)]) / (m - 1);
    double contrast = (sum[static_cast<std::size_t>(top)] - others) / (total / m + 1e-9);
    if (m == 2 || m == 6) contrast /= 1.2;
    if (contrast > best_contrast) {
      best_contrast = contrast;
      best = {m, top};
    }
  }
  // The phase of that meter with the change of sound counted too: where instruments enter and
  // leave tells which beat of the bar is the first, not how long the bar is (a sound that
  // changes at one beat changes back two beats later).
  std::vector<double> marked(static_cast<std::size_t>(best.beats), 0.0);
  for (std::size_t i = 0; i < beats.size(); ++i) {
    marked[i % static_cast<std::size_t>(best.beats)] += beats[i].accent + beats[i].texture;
  }
  best.phase = static_cast<int>(std::max_element(marked.begin(), marked.end()) - marked.begin());
  return best;
}

// Stretches of steady tempo, each starting on a bar line (the first at beat 0), as the beat
// indices where they start and, last, the end: the split that minimises the squared residuals
// of a line per stretch plus a cost per stretch that a chance improvement from noise does not
// pay (25 sigma^2, over eight times what one more stretch gains on jitter alone on average).
// Empty when no stretch has 8 beats with onsets.
std::vector<std::size_t> split_stretches(const std::vector<Beat>& beats, const BarPhase& bar,
                                         double sigma) {
  const PrefixSums sums(beats);
  std::vector<std::size_t> cuts{0};
  for (auto c = static_cast<std::size_t>(bar.phase + bar.beats); c < beats.size();
       c += static_cast<std::size_t>(bar.beats)) {
    cuts.push_back(c);
  }
  cuts.push_back(beats.size());
  const double penalty = 25.0 * sigma * sigma;
  const std::size_t min_beats = 4 * static_cast<std::size_t>(bar.beats);
  const std::size_t nc = cuts.size();
  std::vector<double> cost(nc, std::numeric_limits<double>::infinity());
  std::vector<std::size_t> from(nc, 0);
  cost[0] = 0;
  for (std::size_t k = 1; k < nc; ++k) {
    for (std::size_t j = 0; j < k; ++j) {
      if (!std::isfinite(cost[j])) continue;
      const bool whole = j == 0 && k == nc - 1;
      if (!whole && cuts[k] - cuts[j] < min_beats) continue;
      const LineFit f = sums.fit(cuts[j], cuts[k]);
      if (f.count < 8) continue;
      const double c = cost[j] + f.sse + penalty;
      if (c < cost[k]) {
        cost[k] = c;
        from[k] = j;
      }
    }
  }
  if (!std::isfinite(cost[nc - 1])) return {};
  std::vector<std::size_t> bounds{beats.size()};
  for (std::size_t k = nc - 1; k != 0; k = from[k]) bounds.push_back(cuts[from[k]]);
  std::reverse(bounds.begin(), bounds.end());

  return bounds;
}

// A change the ear cannot follow, or one the onsets' own unevenness explains, is noise in the
// map: two neighbouring stretches are one when a single line through both stays within 15 ms
// of each bar's beats, or within 3.5 times the bars' own scatter about their stretches' lines
// when that is more (the onsets of a band playing to a click wander from sound to sound),
// allowing two bars in a row within twice that (a fill, where the onsets are another
// instrument's). A real change of tempo, or a drift, puts every bar after it further off. The
// closest pair is joined first.
void merge_inaudible_changes(const std::vector<Beat>& beats, const PrefixSums& sums, int per_bar,
                             double floor, std::vector<std::size_t>& bounds) {
  std::vector<double> offsets = bar_offsets(beats, sums, bounds, per_bar);
  for (double& o : offsets) o = std::abs(o);
  double scatter = 0;
  if (!offsets.empty()) {
    std::nth_element(offsets.begin(), offsets.begin() + long(offsets.size() / 2), offsets.end());
    scatter = 1.4826 * offsets[offsets.size() / 2];
  }
  const double audible = std::max(floor, 3.5 * scatter);
  while (bounds.size() > 2) {
    std::size_t best = 0;
    Stray best_stray{std::numeric_limits<int>::max(), 0};
    for (std::size_t s = 0; s + 2 < bounds.size(); ++s) {
      const Stray stray =
          stray_if_joined(beats, sums, bounds[s], bounds[s + 1], bounds[s + 2], per_bar, audible);
      if (std::tie(stray.run, stray.worst) < std::tie(best_stray.run, best_stray.worst)) {
        best_stray = stray;
        best = s;
      }
    }
    if (best_stray.run >= 3 || best_stray.worst > 2 * audible) return;
    bounds.erase(bounds.begin() + long(best + 1));
  }
}

int decimals_for(const LineFit& fit, double sigma) {
  const double residual = fit.count > 2 ? std::sqrt(fit.sse / (fit.count - 2)) : sigma;
  // At least 1 ms per beat: placing a kick's onset and a snare's is good to about that, and
  // the difference repeats with the pattern rather than averaging out.
  const double slope_error = std::max({residual, sigma, 1e-3}) / std::sqrt(fit.sxx);
  const double tempo_error = 60.0 * slope_error / (fit.b * fit.b);
  // The last digit shown is no finer than two standard errors.
  const double digits = std::floor(std::log10(1.0 / (2.0 * tempo_error)));
  return static_cast<int>(std::clamp(digits, 0.0, 3.0));
}

// A map is read as one chain: each stretch starts where the one before it ends at its printed
// tempo (docs/music.md), not where its own line puts it. Each change's bar line is set where
// the lines on either side of it meet it (their mean), and each stretch but the last gets the
// tempo that reaches the next bar line from where the printed map so far stands, printed with
// enough decimals that its rounding moves that bar line by less than half a millisecond: the
// chain stays on the song's beats however many changes it has.
void make_continuous(TempoMap& map, const std::vector<std::size_t>& bounds,
                     const PrefixSums& sums) {
  const std::size_t count = map.stretches.size();
  if (count < 2 || bounds.size() != count + 1) return;
  const int per_bar = map.meter.beats;
  double printed = map.stretches.front().start_s;
  for (std::size_t j = 0; j + 1 < count; ++j) {
    TempoStretch& here = map.stretches[j];
    const TempoStretch& next = map.stretches[j + 1];
    const LineFit before = sums.fit(bounds[j], bounds[j + 1]);
    const LineFit after = sums.fit(bounds[j + 1], bounds[j + 2]);
    const double at = double(bounds[j + 1]);
    const double knot = 0.5 * ((before.a + before.b * at) + (after.a + after.b * at));
    const double beats = double((next.bar - here.bar) * per_bar);
    here.start_s = printed;
    here.tempo = 60.0 * beats / (knot - printed);
    const double duration = knot - printed;
    const double needed = std::ceil(std::log10(duration / (0.001 * here.tempo)));
    here.decimals = std::max(here.decimals, static_cast<int>(std::clamp(needed, 0.0, 3.0)));
    const double shown = std::stod(tempo_text(here.tempo, here.decimals));
    printed += beats * 60.0 / shown;
  }
  map.stretches.back().start_s = printed;
}

// Beat `k` of the printed chain (0 is bar 1 beat 1; negative counts back from it at the first
// stretch's tempo), each stretch at its printed tempo.
double chain_time(const TempoMap& map, long k) {
  const auto shown = [](const TempoStretch& s) {
    return std::stod(tempo_text(s.tempo, s.decimals));
  };
  for (std::size_t j = 0; j < map.stretches.size(); ++j) {
    const TempoStretch& s = map.stretches[j];
    const bool last = j + 1 == map.stretches.size();
    const long length = last ? 0 : long(map.stretches[j + 1].bar - s.bar) * map.meter.beats;
    if (k < 0 || last || k < length) return s.start_s + double(k) * 60.0 / shown(s);
    k -= length;
  }
  return 0;
}

}  // namespace seqc::music
