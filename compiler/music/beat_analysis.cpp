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

#include "compiler/music/bar_map.hpp"
#include "compiler/music/beat_placement.hpp"
#include "compiler/music/beat_tracking.hpp"
#include "compiler/music/onset_envelope.hpp"

namespace seqc::music {
namespace {

constexpr double kMinSeconds = 6.0;

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
