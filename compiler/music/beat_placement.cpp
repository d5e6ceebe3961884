#include "compiler/music/beat_placement.hpp"

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

#include "compiler/music/beat_tracking.hpp"

namespace seqc::music {
namespace {

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

}  // namespace

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

}  // namespace seqc::music
