#include "compiler/music/beat_analysis.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <limits>
#include <numeric>

#include "compiler/music/beat_tracking.hpp"
#include "compiler/music/onset_envelope.hpp"

namespace seqc::music {
namespace {

constexpr double kMinSeconds = 6.0;

struct Beat {
  double time_s = 0;       // the onset, or the tracker's frame when there is none
  bool has_onset = false;  // a clear rise in amplitude near the tracked frame
  double rise = 0;         // how much the amplitude rose at the onset
  double accent = 0;       // how strongly the beat is marked (bar lines are, in most music)
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
Beat place_on_onset(int frame, double period_frames, const OnsetEnvelope& env,
                    const FineEnvelope& fine, double analysis_rate) {
  Beat beat;
  const double frame_s = double(frame) * double(env.hop) / analysis_rate;
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
  beat.rise = peak - before;
  return beat;
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
// bar, the mean low-band accent of its beats; the meter whose strongest phase stands out most
// from its others wins, and that phase is the downbeat.
struct BarPhase {
  int beats = 4;
  int phase = 0;  // index (among the kept beats) of the first downbeat
};
BarPhase bar_phase(const std::vector<Beat>& beats, std::optional<int> given) {
  BarPhase best;
  double best_contrast = -std::numeric_limits<double>::infinity();
  std::vector<int> meters = given ? std::vector<int>{*given} : std::vector<int>{4, 3};
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
    const double contrast = (sum[static_cast<std::size_t>(top)] - others) / (total / m + 1e-9);
    if (contrast > best_contrast) {
      best_contrast = contrast;
      best = {m, top};
    }
  }
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

Error no_steady_beat(const char* why) {
  return make_error(std::string("no steady beat found (") + why +
                    "); --tempo-hint or --meter may help if the music has one");
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
  const std::vector<double> periods = local_periods(env.flux, env.frame_rate, tempo->period);
  const std::vector<int> frames = track_beats(env.flux, periods);

  std::vector<Beat> beats;
  std::vector<double> lows;
  double low_sum = 0, rise_sum = 0;
  for (int f : frames) {
    const auto u = static_cast<std::size_t>(f);
    beats.push_back(place_on_onset(f, periods[u], env, fine, signal.sample_rate));
    double low = 0;
    for (std::size_t k = u > 0 ? u - 1 : 0; k <= u + 2 && k < env.low.size(); ++k) {
      low = std::max(low, env.low[k]);
    }
    lows.push_back(low);
    low_sum += low;
    rise_sum += beats.back().rise;
  }
  // An onset a thirtieth of the typical one (-30 dB) is the decay of a note or noise, not a
  // beat; a quiet intro at -20 dB still counts.
  std::vector<double> rises;
  for (const Beat& b : beats) {
    if (b.has_onset) rises.push_back(b.rise);
  }
  if (!rises.empty()) {
    std::nth_element(rises.begin(), rises.begin() + long(rises.size() / 2), rises.end());
    const double typical = rises[rises.size() / 2];
    for (Beat& b : beats) {
      if (b.rise < typical / 30) b.has_onset = false;
    }
  }
  // A bar's first beat is usually the one with the bass note and the kick, and the loudest:
  // the low band's onset counts twice as much as the loudness of the onset.
  for (std::size_t i = 0; i < beats.size(); ++i) {
    beats[i].accent = (low_sum > 0 ? lows[i] / low_sum : 0.0) +
                      0.5 * (rise_sum > 0 ? beats[i].rise / rise_sum : 0.0);
  }
  std::optional<int> given_beats;
  if (options.meter) given_beats = options.meter->beats;
  BarPhase bar;
  double sigma = 0;
  std::vector<std::size_t> bounds;
  // A spurious onset (noise before the music, a fill) would pull a stretch's line towards it:
  // onsets far off the fitted lines are dropped and the map is made again, until none is.
  for (int round = 0;; ++round) {
    // The song's beats run from the first to the last beat with an onset: the tracker also
    // fills silence and noise before and after the music with beats.
    const auto first =
        std::find_if(beats.begin(), beats.end(), [](const Beat& b) { return b.has_onset; });
    const auto last =
        std::find_if(beats.rbegin(), beats.rend(), [](const Beat& b) { return b.has_onset; });
    if (first == beats.end()) return no_steady_beat("no clear onsets");
    beats = std::vector<Beat>(first, last.base());
    if (beats.size() < 16) return no_steady_beat("fewer than 16 beats");
    bar = bar_phase(beats, given_beats);
    sigma = jitter_sigma(beats);
    bounds = split_stretches(beats, bar, sigma);
    if (bounds.empty()) return no_steady_beat("too few beats with onsets");
    const PrefixSums sums(beats);
    bool dropped = false;
    for (std::size_t s = 0; s + 1 < bounds.size(); ++s) {
      const LineFit f = sums.fit(bounds[s], bounds[s + 1]);
      for (std::size_t i = bounds[s]; i < bounds[s + 1]; ++i) {
        // The residual from the line fitted without this beat (r / (1 - leverage)): a stray
        // onset at the end of a stretch pulls the line towards itself.
        const double leverage = 1.0 / f.count + (double(i) - f.xbar) * (double(i) - f.xbar) / f.sxx;
        const double residual =
            (beats[i].time_s - (f.a + f.b * double(i))) / std::max(1e-3, 1.0 - leverage);
        if (beats[i].has_onset && std::abs(residual) > std::max(5 * sigma, 0.04 * f.b)) {
          beats[i].has_onset = false;
          dropped = true;
        }
      }
    }
    if (!dropped || round == 4) break;
  }
  const PrefixSums sums(beats);

  BeatAnalysis result;
  result.map.meter = options.meter ? *options.meter : Meter{bar.beats, 4};
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

  std::vector<double> onsets;
  for (const Beat& b : beats) {
    result.beats_s.push_back(b.time_s);
    if (b.has_onset) onsets.push_back(b.time_s);
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
  if (result.confidence < 0.5) {
    char text[64];
    std::snprintf(text, sizeof text, "confidence %.2f", result.confidence);
    return no_steady_beat(text);
  }
  return result;
}

}  // namespace seqc::music
