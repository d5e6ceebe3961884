#include "compiler/music/beat_analysis.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <limits>
#include <numeric>
#include <string>
#include <tuple>

#include "compiler/music/beat_tracking.hpp"
#include "compiler/music/onset_envelope.hpp"

namespace seqc::music {
namespace {

constexpr double kMinSeconds = 6.0;

struct Beat {
  double frame = 0;        // where the tracker put it, in envelope frames
  double time_s = 0;       // the onset, or the tracker's frame when there is none
  bool has_onset = false;  // a clear onset near the tracked frame
  bool fine = false;       // placed on the amplitude envelope (a hit standing out of silence)
  double rise = 0;         // how much the amplitude rose at the onset
  double strength = 0;     // the onset envelope's peak near the beat (unit: its RMS)
  double accent = 0;       // how strongly the beat is marked (bar lines are, in most music)
  double texture = 0;      // how much the sound changes there, over its mean: picks the phase
};

double mean(const std::vector<double>& x, long long from, long long to) {
  from = std::max(0LL, from);
  to = std::min(static_cast<long long>(x.size()), to);
  if (to <= from) return 0;
  double sum = 0;
  for (long long i = from; i < to; ++i) sum += x[static_cast<std::size_t>(i)];
  return sum / double(to - from);
}

// Places a tracked beat on the onset near it: the block where the mean amplitude of the next
// 4 ms rises most over that of the 4 ms before, then the point where the amplitude crosses 30%
// of the way from before to the peak after (linear between block centres).
Beat place_on_onset(double frame, double period_frames, const OnsetEnvelope& env,
                    const FineEnvelope& fine, double analysis_rate) {
  Beat beat;
  beat.frame = frame;
  const double frame_s = frame * double(env.hop) / analysis_rate;
  beat.time_s = frame_s;
  const double period_s = period_frames / env.frame_rate;
  // The tracker's frame can be off the onset by a few frames either way (its interval penalty
  // pulls it); a fifth of a beat, at most 60 ms, stays clear of off-beat eighths.
  const double reach_s = std::min(0.2 * period_s, 0.06);
  const double from_s = frame_s - reach_s;
  const double to_s = frame_s + reach_s;
  const auto from = static_cast<long long>(std::floor(from_s * fine.block_rate));
  const auto to = static_cast<long long>(std::ceil(to_s * fine.block_rate));
  const std::vector<double>& a = fine.amplitude;
  constexpr long long kSpan = 8;  // blocks either side: about 4 ms
  long long best = -1;
  double best_rise = 0;
  for (long long k = std::max(kSpan, from); k <= to && k + kSpan < static_cast<long long>(a.size());
       ++k) {
    const double rise = mean(a, k, k + kSpan) - mean(a, k - kSpan, k);
    if (rise > best_rise) {
      best_rise = rise;
      best = k;
    }
  }
  if (best < 0) return beat;
  const double before = mean(a, best - kSpan, best);
  double peak = 0;
  for (long long k = best; k < best + 3 * kSpan && k < static_cast<long long>(a.size()); ++k) {
    peak = std::max(peak, a[static_cast<std::size_t>(k)]);
  }
  // The level doubling (+6 dB): a hit, not the wobble of noise or a held note.
  if (best_rise < 1.0 * before || peak < 1e-4) return beat;
  const double threshold = before + 0.3 * (peak - before);
  long long k = best;
  while (k > best - kSpan && a[static_cast<std::size_t>(k - 1)] >= threshold) --k;
  while (k < best + kSpan && a[static_cast<std::size_t>(k)] < threshold) ++k;
  const double lo = a[static_cast<std::size_t>(k - 1)], hi = a[static_cast<std::size_t>(k)];
  const double frac = hi > lo ? std::clamp((threshold - lo) / (hi - lo), 0.0, 1.0) : 1.0;
  // Block k's amplitude stands for its centre, k + 0.5 blocks.
  beat.time_s = (double(k) - 0.5 + frac) / fine.block_rate;
  beat.has_onset = true;
  beat.fine = true;
  beat.rise = peak - before;
  return beat;
}

// The tracker's beats with the ones it skipped put back: an interval of about k periods (a
// break, a stop) holds k - 1 beats evenly spaced, so every beat's index counts whole beats from
// the first and one line fits them all.
std::vector<double> whole_beats(const std::vector<int>& frames,
                                const std::vector<double>& periods) {
  std::vector<double> out;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    if (i > 0) {
      const double gap = double(frames[i] - frames[i - 1]);
      const double p = periods[static_cast<std::size_t>(frames[i])];
      const long k = std::lround(gap / p);
      for (long j = 1; j < k; ++j)
        out.push_back(double(frames[i - 1]) + gap * double(j) / double(k));
    }
    out.push_back(double(frames[i]));
  }
  return out;
}

// Each beat on its onset: on the amplitude envelope where a hit stands out of what is before it
// (a click, a drum in a sparse mix), else on the fine band flux, which finds a kick or a snare
// inside a dense mix. The two mark an onset at slightly different instants: the flux's times
// are moved by the median difference of the beats both place, so one line fits them all.
std::vector<Beat> place_beats(const std::vector<double>& frames, const std::vector<double>& periods,
                              const OnsetEnvelope& env, const FineEnvelope& fine,
                              const AnalysisSignal& signal) {
  std::vector<Beat> beats;
  std::vector<double> flux_times, differences;
  for (double f : frames) {
    const auto u = std::min(static_cast<std::size_t>(std::lround(f)), env.flux.size() - 1);
    Beat beat = place_on_onset(f, periods[u], env, fine, signal.sample_rate);
    // The envelope's peak within a frame either side: the tracker may sit beside it.
    for (std::size_t k = u > 0 ? u - 1 : 0; k <= u + 1 && k < env.flux.size(); ++k) {
      beat.strength = std::max(beat.strength, env.flux[k]);
    }
    const double frame_s = f / env.frame_rate;
    const double reach_s = std::min(0.15 * periods[u] / env.frame_rate, 0.05);
    const FinePeak peak = fine_flux_peak(signal, frame_s - reach_s, frame_s + reach_s);
    flux_times.push_back(peak.time_s);
    if (beat.fine && peak.time_s >= 0) differences.push_back(beat.time_s - peak.time_s);
    beats.push_back(beat);
  }
  double shift = 0;
  if (!differences.empty()) {
    std::nth_element(differences.begin(), differences.begin() + long(differences.size() / 2),
                     differences.end());
    shift = differences[differences.size() / 2];
  }
  // An onset at least a third of the typical beat's (the envelope is at unit RMS, so the
  // off-beat texture of a dense mix stays under it).
  std::vector<double> strengths;
  for (const Beat& b : beats) strengths.push_back(b.strength);
  std::nth_element(strengths.begin(), strengths.begin() + long(strengths.size() / 2),
                   strengths.end());
  const double floor = strengths.empty() ? 0.0 : strengths[strengths.size() / 2] / 3;
  for (std::size_t i = 0; i < beats.size(); ++i) {
    Beat& b = beats[i];
    if (b.fine || flux_times[i] < 0 || b.strength <= floor || b.strength < 0.5) continue;
    b.time_s = flux_times[i] + shift;
    b.has_onset = true;
    b.rise = -1;  // not measured on the amplitude: kept by the strength test only
  }
  return beats;
}

// How much the harmony changes at each beat: one minus the cosine between the pitch classes of
// the two beats from it and those of the two beats before it (0 where it stays, towards 1 at a
// new chord). Chords change on bar lines far more often than between them.
std::vector<double> chord_changes(const std::vector<Beat>& beats, const OnsetEnvelope& env) {
  const std::size_t n = beats.size();
  std::vector<std::array<double, 12>> per_beat(n);
  for (std::size_t i = 0; i < n; ++i) {
    const auto from = static_cast<std::size_t>(std::max(0L, std::lround(beats[i].frame)));
    const auto to =
        i + 1 < n ? static_cast<std::size_t>(std::lround(beats[i + 1].frame)) : from + 1;
    per_beat[i].fill(0.0);
    for (std::size_t f = from; f < to && f < env.chroma.size(); ++f) {
      for (std::size_t c = 0; c < 12; ++c) per_beat[i][c] += env.chroma[f][c];
    }
  }
  std::vector<double> change(n, 0.0);
  for (std::size_t i = 2; i + 1 < n; ++i) {
    double dot = 0, before = 0, after = 0;
    for (std::size_t c = 0; c < 12; ++c) {
      const double a = per_beat[i][c] + per_beat[i + 1][c];
      const double b = per_beat[i - 1][c] + per_beat[i - 2][c];
      dot += a * b;
      after += a * a;
      before += b * b;
    }
    if (before > 0 && after > 0) change[i] = 1.0 - dot / std::sqrt(before * after);
  }
  return change;
}

// How much the sound changes at each beat: the distance between the mean band levels of the
// `per_bar` beats from it and of the `per_bar` beats before it. Instruments enter and leave,
// sections begin and end, on bar lines; a bar cut anywhere else straddles the change and halves it.
std::vector<double> texture_changes(const std::vector<Beat>& beats, const OnsetEnvelope& env,
                                    int per_bar) {
  const std::size_t n = beats.size();
  const std::size_t bands = env.levels.empty() ? 0 : env.levels.front().size();
  std::vector<std::vector<double>> per_beat(n, std::vector<double>(bands, 0.0));
  for (std::size_t i = 0; i < n; ++i) {
    const auto from = static_cast<std::size_t>(std::max(0L, std::lround(beats[i].frame)));
    const auto to =
        i + 1 < n ? static_cast<std::size_t>(std::lround(beats[i + 1].frame)) : from + 1;
    std::size_t count = 0;
    for (std::size_t f = from; f < to && f < env.levels.size(); ++f, ++count) {
      for (std::size_t b = 0; b < bands; ++b) per_beat[i][b] += env.levels[f][b];
    }
    if (count > 0) {
      for (double& v : per_beat[i]) v /= double(count);
    }
  }
  const auto span = static_cast<std::size_t>(per_bar);
  std::vector<double> change(n, 0.0);
  for (std::size_t i = span; i + span <= n; ++i) {
    double sum = 0;
    for (std::size_t b = 0; b < bands; ++b) {
      double after = 0, before = 0;
      for (std::size_t k = 0; k < span; ++k) {
        after += per_beat[i + k][b];
        before += per_beat[i - 1 - k][b];
      }
      const double d = (after - before) / double(span);
      sum += d * d;
    }
    change[i] = std::sqrt(sum);
  }
  return change;
}

// Least squares t = a + b * i over the beats in [from, to) that have onsets.
struct LineFit {
  double a = 0, b = 0;
  double sse = 0;
  double sxx = 0;   // spread of the indices, for the slope's standard error
  double xbar = 0;  // mean index
  int count = 0;
};

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
struct BarPhase {
  int beats = 4;
  int phase = 0;  // index (among the kept beats) of the first downbeat
};
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

Error no_steady_beat(const char* why) {
  return make_error(std::string("no steady beat found (") + why +
                    "); --tempo-hint or --meter may help if the music has one");
}

// The map from beat frames (ascending, whole beats apart): each beat placed on its onset, the
// meter and downbeat, the stretches and the confidence; or why there is none.
Result<BeatAnalysis> map_from_beats(const std::vector<double>& frames,
                                    const std::vector<double>& periods, const OnsetEnvelope& env,
                                    const FineEnvelope& fine, const AnalysisSignal& signal,
                                    const BeatOptions& options, bool on_grid) {
  std::vector<Beat> beats = place_beats(frames, periods, env, fine, signal);

  std::vector<double> lows;
  double low_sum = 0, rise_sum = 0;
  for (const Beat& b : beats) {
    const auto u = static_cast<std::size_t>(std::lround(b.frame));
    double low = 0;
    for (std::size_t k = u > 0 ? u - 1 : 0; k <= u + 2 && k < env.low.size(); ++k) {
      low = std::max(low, env.low[k]);
    }
    lows.push_back(low);
    low_sum += low;
    rise_sum += std::max(0.0, b.rise);
  }
  // An onset a thirtieth of the typical one (-30 dB) is the decay of a note or noise, not a
  // beat; a quiet intro at -20 dB still counts.
  std::vector<double> rises;
  for (const Beat& b : beats) {
    if (b.fine) rises.push_back(b.rise);
  }
  if (!rises.empty()) {
    std::nth_element(rises.begin(), rises.begin() + long(rises.size() / 2), rises.end());
    const double typical = rises[rises.size() / 2];
    for (Beat& b : beats) {
      if (b.fine && b.rise < typical / 30) b.has_onset = false;
    }
  }
  // A bar's first beat is usually where the chord changes and instruments enter or leave, with
  // the bass note and the kick, and the loudest: each cue over its mean, the low band's onset,
  // the chord change and the change of sound counting twice as much as the loudness.
  const std::vector<double> changes = chord_changes(beats, env);
  const std::vector<double> textures = texture_changes(beats, env, 2);
  double change_sum = 0, strength_sum = 0, texture_sum = 0;
  for (std::size_t i = 0; i < beats.size(); ++i) {
    change_sum += changes[i];
    strength_sum += beats[i].strength;
    texture_sum += textures[i];
  }
  for (std::size_t i = 0; i < beats.size(); ++i) {
    const double n = double(beats.size());
    beats[i].texture = texture_sum > 0 ? n * textures[i] / texture_sum : 0.0;
    beats[i].accent = (low_sum > 0 ? n * lows[i] / low_sum : 0.0) +
                      (change_sum > 0 ? n * changes[i] / change_sum : 0.0) +
                      0.5 * (rise_sum > 0 ? n * std::max(0.0, beats[i].rise) / rise_sum : 0.0) +
                      0.5 * (strength_sum > 0 ? n * beats[i].strength / strength_sum : 0.0);
  }
  std::optional<int> given_beats;
  if (options.meter) given_beats = options.meter->beats;
  BarPhase bar;
  double sigma = 0;
  std::vector<std::size_t> bounds;
  // A spurious onset (noise before the music, a fill) would pull a stretch's line towards it:
  // onsets far off the fitted lines are dropped and the map is made again, until none is.
  // The song's beats run from the first to the last beat with an onset: the tracker also fills
  // silence and noise before and after the music with beats.
  const auto first =
      std::find_if(beats.begin(), beats.end(), [](const Beat& b) { return b.has_onset; });
  const auto last =
      std::find_if(beats.rbegin(), beats.rend(), [](const Beat& b) { return b.has_onset; });
  if (first == beats.end()) return no_steady_beat("no clear onsets");
  beats = std::vector<Beat>(first, last.base());
  if (beats.size() < 16) return no_steady_beat("fewer than 16 beats");
  std::vector<bool> heard;
  for (const Beat& b : beats) heard.push_back(b.has_onset);
  // Each round judges every onset heard against the lines of the round before, so an onset
  // dropped against one line for a drifting song comes back once the song has its stretches.
  for (int round = 0;; ++round) {
    bar = bar_phase(beats, given_beats);
    sigma = jitter_sigma(beats);
    bounds = split_stretches(beats, bar, sigma);
    if (bounds.empty()) return no_steady_beat("too few beats with onsets");
    const PrefixSums sums(beats);
    bool changed = false;
    for (std::size_t s = 0; s + 1 < bounds.size(); ++s) {
      const LineFit f = sums.fit(bounds[s], bounds[s + 1]);
      for (std::size_t i = bounds[s]; i < bounds[s + 1]; ++i) {
        // The residual from the line fitted without this beat (r / (1 - leverage)): a stray
        // onset at the end of a stretch pulls the line towards itself.
        const double leverage = 1.0 / f.count + (double(i) - f.xbar) * (double(i) - f.xbar) / f.sxx;
        const double residual =
            (beats[i].time_s - (f.a + f.b * double(i))) / std::max(1e-3, 1.0 - leverage);
        const bool keep = heard[i] && std::abs(residual) <= std::max(5 * sigma, 0.04 * f.b);
        if (keep != beats[i].has_onset) {
          beats[i].has_onset = keep;
          changed = true;
        }
      }
    }
    if (!changed || round == 4) break;
  }
  const PrefixSums sums(beats);
  merge_inaudible_changes(beats, sums, bar.beats, on_grid ? 0.030 : 0.015, bounds);

  BeatAnalysis result;
  // Six beats to the bar are eighths (6/8); two, three and four are quarters.
  result.map.meter = options.meter ? *options.meter : Meter{bar.beats, bar.beats == 6 ? 8 : 4};
  result.meter_detected = !options.meter;
  std::size_t s = 0;
  while (s + 1 < bounds.size()) {
    const LineFit f = sums.fit(bounds[s], bounds[s + 1]);
    const std::size_t start = s == 0 ? static_cast<std::size_t>(bar.phase) : bounds[s];
    TempoStretch stretch;
    stretch.bar = static_cast<int>((start - static_cast<std::size_t>(bar.phase)) /
                                   static_cast<std::size_t>(bar.beats)) +
                  1;
    stretch.start_s = f.a + f.b * double(start);
    stretch.tempo = 60.0 / f.b;
    stretch.decimals = decimals_for(f, sigma);
    // Two stretches that print the same tempo are one to a reader: join them and fit the
    // joined stretch again.
    if (!result.map.stretches.empty() &&
        tempo_text(result.map.stretches.back().tempo, result.map.stretches.back().decimals) ==
            tempo_text(stretch.tempo, stretch.decimals)) {
      bounds.erase(bounds.begin() + long(s));
      result.map.stretches.pop_back();
      --s;
      continue;
    }
    result.map.stretches.push_back(stretch);
    ++s;
  }
  make_continuous(result.map, bounds, sums);

  std::vector<double> onsets;
  for (std::size_t i = 0; i < beats.size(); ++i) {
    // A beat without an onset on the map (a rest, a stray hit left out) is where the map puts
    // it, so the list never leaves the map's beats.
    result.beats_s.push_back(beats[i].has_onset
                                 ? beats[i].time_s
                                 : chain_time(result.map, static_cast<long>(i) - bar.phase));
    const long place = (static_cast<long>(i) - bar.phase) % bar.beats;
    result.positions.push_back(static_cast<int>((place + bar.beats) % bar.beats) + 1);
    if (beats[i].has_onset) onsets.push_back(beats[i].time_s);
  }
  const std::vector<MapBeat> grid =
      map_beats(result.map, onsets.front() - 1e-3, onsets.back() + 1e-3);
  int hits = 0;
  for (const MapBeat& g : grid) {
    const auto it = std::lower_bound(onsets.begin(), onsets.end(), g.time_s);
    double nearest = std::numeric_limits<double>::infinity();
    if (it != onsets.end()) nearest = *it - g.time_s;
    if (it != onsets.begin()) nearest = std::min(nearest, g.time_s - *(it - 1));
    if (nearest <= 0.1 * 60.0 / result.map.stretches.front().tempo) ++hits;
  }
  result.confidence = grid.empty() ? 0.0 : double(hits) / double(grid.size());
  std::vector<double> distances;
  for (std::size_t i = 0; i < beats.size(); ++i) {
    if (!beats[i].has_onset) continue;
    distances.push_back(
        std::abs(beats[i].time_s - chain_time(result.map, static_cast<long>(i) - bar.phase)));
  }
  if (!distances.empty()) {
    std::nth_element(distances.begin(), distances.begin() + long(distances.size() / 2),
                     distances.end());
    result.spread_s = distances[distances.size() / 2];
  }
  if (result.confidence < 0.35) {
    char text[64];
    std::snprintf(text, sizeof text, "confidence %.2f", result.confidence);
    return no_steady_beat(text);
  }
  return result;
}

}  // namespace

Result<BeatAnalysis> analyze_beats(std::span<const float> samples, double sample_rate,
                                   const BeatOptions& options) {
  const double seconds = sample_rate > 0 ? double(samples.size()) / sample_rate : 0;
  if (seconds < kMinSeconds) {
    char text[128];
    std::snprintf(text, sizeof text, "too short to find a beat (%.1f s; at least %.0f s)", seconds,
                  kMinSeconds);
    return make_error(text);
  }
  const AnalysisSignal signal = reduce_for_analysis(samples, sample_rate);
  const OnsetEnvelope env = onset_envelope(signal);
  const FineEnvelope fine = fine_envelope(signal);
  std::optional<double> hint_period;
  if (options.tempo_hint) hint_period = 60.0 * env.frame_rate / *options.tempo_hint;
  const auto tempo = estimate_tempo(env.flux, env.low, env.frame_rate, hint_period);
  if (!tempo || tempo->strength < 0.05) return no_steady_beat("no repeating onsets");
  // The span with onsets: the levels' grids are laid over it.
  std::size_t first_onset = 0, last_onset = 0;
  for (std::size_t f = 0; f < env.flux.size(); ++f) {
    if (env.flux[f] >= 1.0) {
      if (last_onset == 0) first_onset = f;
      last_onset = f;
    }
  }
  const LevelScore level = choose_level(env.flux, env.low, env.frame_rate, tempo->period,
                                        first_onset, last_onset, hint_period);
  // Below 1.5 the beat stands out of the music no more than a grid laid over noise does.
  if (level.salience > 0 && level.salience < 1.5) {
    char text[96];
    std::snprintf(text, sizeof text, "its strongest pulse stands only %.2f times above the music",
                  level.salience);
    return no_steady_beat(text);
  }
  const double period = level.period;
  const std::vector<double> periods = local_periods(env.flux, env.frame_rate, period);
  const std::vector<double> frames = whole_beats(track_beats(env.flux, periods), periods);
  Result<BeatAnalysis> tracked = map_from_beats(frames, periods, env, fine, signal, options, false);
  if (frames.size() >= 16) {
    // Music played to a click: one steady grid for the whole song keeps its beats through
    // breaks, fills and passages where the off-beats are louder, where the tracker can slip by
    // half a beat or follow another level for a while. Its map is taken when its beats have
    // onsets about as often as the tracked map's do (a song that drifts or changes tempo
    // leaves the grid, and the grid's map loses its onsets). The grid is one tempo, so its map
    // is one stretch: where its onsets lean one way for a while (another instrument carries the
    // beat), the grid, not a change of tempo, is the song's.
    const SteadyGrid grid = steady_grid(env.flux, period, static_cast<std::size_t>(frames.front()),
                                        static_cast<std::size_t>(frames.back()));
    // The tracked map wins where the tracked beats land on onsets clearly more often than
    // the grid's (a drift, a change of tempo or a jump moves the song off the grid); counted on
    // the onset envelope, which neither placed its beats by.
    const std::vector<double> steady_frames = grid_frames(grid, frames.front(), frames.back());
    const bool tracked_better =
        tracked.ok() && onset_share(env.flux, steady_frames) < 0.75 * onset_share(env.flux, frames);
    if (!tracked_better) {
      Result<BeatAnalysis> steady =
          map_from_beats(steady_frames, periods, env, fine, signal, options, true);
      if (steady.ok()) return steady;
    }
  }
  return tracked;
}

std::string beat_list(const BeatAnalysis& analysis) {
  std::string out;
  char line[64];
  for (std::size_t i = 0; i < analysis.beats_s.size(); ++i) {
    std::snprintf(line, sizeof line, "%.3f\t%d\n", analysis.beats_s[i], analysis.positions[i]);
    out += line;
  }
  return out;
}

std::string analysis_summary(const BeatAnalysis& analysis) {
  char line[160];
  std::snprintf(line, sizeof line,
                "%zu beats, confidence %.2f (the share of the map's beats with an onset within a "
                "tenth of a beat)",
                analysis.beats_s.size(), analysis.confidence);
  return line;
}

}  // namespace seqc::music
