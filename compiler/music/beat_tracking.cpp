#include "compiler/music/beat_tracking.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

namespace seqc::music {
namespace {

double autocorrelation(const std::vector<double>& x, std::size_t from, std::size_t to,
                       std::size_t lag) {
  double sum = 0;
  for (std::size_t i = from + lag; i < to; ++i) sum += x[i] * x[i - lag];
  return sum;
}

// Linear interpolation of x at a fractional index (0 outside).
double at(const std::vector<double>& x, double index) {
  if (index < 0 || index >= double(x.size() - 1)) return 0;
  const auto i = static_cast<std::size_t>(index);
  const double frac = index - double(i);
  return x[i] * (1 - frac) + x[i + 1] * frac;
}

// The lag of the largest autocorrelation in [lo, hi], refined by a parabola through its
// neighbours; `weight` scales each lag's value.
template <class Weight>
double peak_lag(const std::vector<double>& acf, std::size_t lo, std::size_t hi, Weight weight) {
  std::size_t best = lo;
  double best_value = -std::numeric_limits<double>::infinity();
  for (std::size_t lag = lo; lag <= hi && lag < acf.size(); ++lag) {
    const double v = acf[lag] * weight(double(lag));
    if (v > best_value) {
      best_value = v;
      best = lag;
    }
  }
  if (best == 0 || best + 1 >= acf.size()) return double(best);
  const double a = acf[best - 1], b = acf[best], c = acf[best + 1];
  const double denom = a - 2 * b + c;
  if (denom >= 0) return double(best);
  return double(best) + std::clamp(0.5 * (a - c) / denom, -0.5, 0.5);
}

// How much weaker the off-beats are than the beats at `period`: the mean envelope half a period
// after each beat over the mean at the beats, at the phase where the beats are strongest, in
// 10 s pieces (a tempo change moves the phase) summed over the song.
double offbeat_ratio(const std::vector<double>& flux, double period, double frame_rate) {
  const auto phases = static_cast<int>(std::ceil(period));
  const double piece = std::max(10.0 * frame_rate, 4 * period);
  double total_on = 0, total_off = 0;
  for (double begin = 0; begin + piece <= double(flux.size()) || begin == 0; begin += piece) {
    double best_on = 0, off_at_best = 0;
    for (int phase = 0; phase < phases; ++phase) {
      double on = 0, off = 0;
      for (double t = begin + phase; t + period < std::min(double(flux.size()), begin + piece);
           t += period) {
        // The largest value within a frame either side: beats fall between frames.
        on += std::max({at(flux, t - 1), at(flux, t), at(flux, t + 1)});
        const double o = t + period / 2;
        off += std::max({at(flux, o - 1), at(flux, o), at(flux, o + 1)});
      }
      if (on > best_on) {
        best_on = on;
        off_at_best = off;
      }
    }
    total_on += best_on;
    total_off += off_at_best;
  }
  return total_on > 0 ? total_off / total_on : 1.0;
}

}  // namespace

std::optional<TempoEstimate> estimate_tempo(const std::vector<double>& flux,
                                            const std::vector<double>& low, double frame_rate,
                                            std::optional<double> hint_period) {
  const auto lo = static_cast<std::size_t>(std::floor(frame_rate * 60.0 / 240.0));
  const auto hi = static_cast<std::size_t>(std::ceil(frame_rate * 60.0 / 40.0));
  if (flux.size() < 4 * hi) return std::nullopt;
  std::vector<double> acf(hi * 2 + 2, 0.0);
  for (std::size_t lag = 0; lag < acf.size(); ++lag) {
    acf[lag] = autocorrelation(flux, 0, flux.size(), lag) / double(flux.size() - lag);
  }
  if (acf[0] <= 0) return std::nullopt;
  // A broad preference for 120 BPM (one octave either side costs a factor of about 0.6) only
  // breaks near-ties between metrical levels; the off-beat test below decides the level.
  const double centre = frame_rate * 0.5;
  auto prior = [&](double lag) {
    const double octaves = std::log2(lag / centre);
    return std::exp(-0.5 * octaves * octaves);
  };
  const double period = peak_lag(acf, lo, hi, prior);
  std::vector<double> levels;
  for (double p : {period / 2, period, period * 2}) {
    const double bpm = 60.0 * frame_rate / p;
    if (bpm >= 50 && bpm <= 230) levels.push_back(p);
  }
  if (levels.empty()) levels.push_back(period);
  // Each level's lag refined on its own peak (the double is not exactly twice the period).
  for (double& p : levels) {
    const auto l = static_cast<std::size_t>(std::max(2.0, std::floor(p * 0.95)));
    const auto h = static_cast<std::size_t>(std::ceil(p * 1.05));
    p = peak_lag(acf, l, std::min(h, acf.size() - 2), [](double) { return 1.0; });
  }
  double chosen = period;
  if (hint_period) {
    double best = std::numeric_limits<double>::infinity();
    for (double p : levels) {
      const double distance = std::abs(std::log(p / *hint_period));
      if (distance < best) {
        best = distance;
        chosen = p;
      }
    }
  } else {
    // The slowest level whose off-beats are clearly weaker: at half the true tempo the
    // "off-beats" are real beats (a snare on 2 and 4), as strong as the beats.
    chosen = levels.front();
    for (double p : levels) {
      const double ratio =
          0.5 * (offbeat_ratio(flux, p, frame_rate) + offbeat_ratio(low, p, frame_rate));
      if (ratio < 0.55) chosen = p;
    }
  }
  const auto lag = static_cast<std::size_t>(std::lround(chosen));
  return TempoEstimate{chosen, std::clamp(acf[std::min(lag, acf.size() - 1)] / acf[0], 0.0, 1.0)};
}

std::vector<double> local_periods(const std::vector<double>& flux, double frame_rate,
                                  double period) {
  const auto window = static_cast<std::size_t>(8.0 * frame_rate);
  const auto step = static_cast<std::size_t>(frame_rate);
  const std::size_t n = flux.size();
  std::vector<double> periods(n, period);
  if (n < window) return periods;
  const auto lo = static_cast<std::size_t>(std::max(2.0, std::floor(period * 0.75)));
  const auto hi = static_cast<std::size_t>(std::ceil(period * 1.3));
  std::vector<double> centres, values;
  for (std::size_t start = 0; start + window <= n; start += step) {
    std::vector<double> acf(hi + 2, 0.0);
    for (std::size_t lag = lo - 1; lag <= hi + 1; ++lag) {
      acf[lag] = autocorrelation(flux, start, start + window, lag);
    }
    centres.push_back(double(start + window / 2));
    values.push_back(peak_lag(acf, lo, hi, [](double) { return 1.0; }));
  }
  // Each frame takes the median of the windows around it: one window fooled by a fill does
  // not bend the tracker.
  for (std::size_t f = 0; f < n; ++f) {
    const double pos = (double(f) - double(window / 2)) / double(step);
    const auto c =
        static_cast<long long>(std::clamp(std::lround(pos), 0L, long(values.size()) - 1));
    std::vector<double> near;
    for (long long k = c - 2; k <= c + 2; ++k) {
      if (k >= 0 && k < static_cast<long long>(values.size())) {
        near.push_back(values[static_cast<std::size_t>(k)]);
      }
    }
    std::nth_element(near.begin(), near.begin() + long(near.size() / 2), near.end());
    periods[f] = near[near.size() / 2];
  }
  return periods;
}

std::vector<int> track_beats(const std::vector<double>& flux, const std::vector<double>& periods) {
  const std::size_t n = flux.size();
  if (n == 0) return {};
  // Tightness 100 as in Ellis 2007 with the envelope at unit std: an interval 10% off the
  // period costs one standard deviation of onset strength.
  constexpr double kTightness = 100.0;
  std::vector<double> score(n, 0.0);
  std::vector<int> previous(n, -1);
  for (std::size_t t = 0; t < n; ++t) {
    const double p = periods[t];
    const auto from = static_cast<long long>(t) - static_cast<long long>(std::lround(2 * p));
    const auto to = static_cast<long long>(t) - static_cast<long long>(std::lround(p / 2));
    double best = -std::numeric_limits<double>::infinity();
    int best_at = -1;
    for (long long s = std::max(0LL, from); s <= to; ++s) {
      const double ratio = std::log(double(static_cast<long long>(t) - s) / p);
      const double v = score[static_cast<std::size_t>(s)] - kTightness * ratio * ratio;
      if (v > best) {
        best = v;
        best_at = static_cast<int>(s);
      }
    }
    // A chain may also start here, as the first beat after silence does: no earlier beat
    // rather than one at a penalised interval.
    if (best_at < 0 || best < 0) {
      best = 0;
      best_at = -1;
    }
    score[t] = flux[t] + best;
    previous[t] = best_at;
  }
  // The last beat: the best score within the final period.
  const auto last_period = static_cast<std::size_t>(std::lround(periods[n - 1]));
  std::size_t end = n - 1;
  for (std::size_t t = n > last_period ? n - last_period : 0; t < n; ++t) {
    if (score[t] > score[end]) end = t;
  }
  std::vector<int> beats;
  for (int t = static_cast<int>(end); t >= 0; t = previous[static_cast<std::size_t>(t)]) {
    beats.push_back(t);
  }
  std::reverse(beats.begin(), beats.end());
  return beats;
}

namespace {

// The comb's value: the envelope summed at every grid beat from `first` to `last`.
double comb(const std::vector<double>& peaks, double period, double phase, std::size_t first,
            std::size_t last) {
  double sum = 0;
  for (double t = double(first) + phase; t <= double(last); t += period) sum += at(peaks, t);
  return sum;
}

}  // namespace

SteadyGrid steady_grid(const std::vector<double>& flux, double period, std::size_t first,
                       std::size_t last) {
  // Each frame's largest value within a frame either side: a grid beat between two frames, or
  // one frame off the onset, still counts it.
  std::vector<double> peaks(flux.size(), 0.0);
  for (std::size_t i = 0; i < flux.size(); ++i) {
    peaks[i] =
        std::max({flux[i], i > 0 ? flux[i - 1] : 0.0, i + 1 < flux.size() ? flux[i + 1] : 0.0});
  }
  last = std::min(last, flux.size() - 1);
  const double beats = std::max(1.0, double(last - first) / period);
  SteadyGrid best{period, 0};
  double best_score = -1;
  // Coarse: the grid's end moves about two frames per step, the phase a frame per step; then
  // fine steps around the best, twice, each a tenth of the one before.
  double step = 2.0 / beats, lo = period * 0.97, hi = period * 1.03, phase_step = 1.0;
  for (int round = 0; round < 3; ++round) {
    for (double p = lo; p <= hi; p += step) {
      const double phase_lo = round == 0 ? 0.0 : best.phase - 2 * phase_step * 10;
      const double phase_hi = round == 0 ? p : best.phase + 2 * phase_step * 10;
      for (double ph = phase_lo; ph < phase_hi; ph += phase_step) {
        const double wrapped = std::fmod(ph + p, p);
        const double score = comb(peaks, p, wrapped, first, last);
        if (score > best_score) {
          best_score = score;
          best = {p, wrapped};
        }
      }
    }
    lo = best.period - 2 * step;
    hi = best.period + 2 * step;
    step /= 10;
    phase_step /= 10;
  }
  best.phase = std::fmod(double(first) + best.phase, best.period);
  return best;
}

double onset_share(const std::vector<double>& flux, const std::vector<double>& frames) {
  std::size_t hits = 0;
  for (double f : frames) {
    const auto u = static_cast<long long>(std::lround(f));
    for (long long k = std::max(0LL, u - 1); k <= u + 1; ++k) {
      if (k < static_cast<long long>(flux.size()) && flux[static_cast<std::size_t>(k)] >= 1.0) {
        ++hits;
        break;
      }
    }
  }
  return frames.empty() ? 0.0 : double(hits) / double(frames.size());
}

std::vector<double> grid_frames(const SteadyGrid& grid, double first, double last) {
  std::vector<double> out;
  const double k0 = std::ceil((first - grid.phase) / grid.period - 0.5);
  for (double f = grid.phase + k0 * grid.period; f <= last + 0.5 * grid.period; f += grid.period) {
    out.push_back(f);
  }
  return out;
}

LevelScore score_level(const std::vector<double>& flux, double period, std::size_t first,
                       std::size_t last) {
  const SteadyGrid grid = steady_grid(flux, period, first, last);
  double on = 0, all = 0;
  std::size_t beats = 0, frames = 0;
  for (double f : grid_frames(grid, double(first), double(last))) {
    on += std::max({at(flux, f - 1), at(flux, f), at(flux, f + 1)});
    ++beats;
  }
  for (std::size_t f = first + 1; f + 1 < last && f + 1 < flux.size(); ++f) {
    all += std::max({flux[f - 1], flux[f], flux[f + 1]});
    ++frames;
  }
  if (beats == 0 || frames == 0 || all <= 0) return {grid.period, 0};
  return {grid.period, (on / double(beats)) / (all / double(frames))};
}

namespace {

bool in_range(double period, double frame_rate) {
  const double bpm = 60.0 * frame_rate / period;
  return bpm >= 40 && bpm <= 240;
}

}  // namespace

LevelScore choose_level(const std::vector<double>& flux, const std::vector<double>& low,
                        double frame_rate, double period, std::size_t first, std::size_t last,
                        std::optional<double> hint_period) {
  last = std::min(last, flux.size() - 1);
  if (double(last) <= double(first) + 4 * period) return {period, 0};
  // The family first: the autocorrelation's level, or the level at two thirds of its period
  // when that one is more strongly marked (a riff in dotted rhythms can make the
  // autocorrelation peak at two thirds of the beat's tempo). Not three halves: when the level
  // is half the beat, three halves of it is three beats, as strongly marked as the beat.
  LevelScore best = score_level(flux, period, first, last);
  if (in_range(period * 2.0 / 3.0, frame_rate)) {
    const LevelScore faster = score_level(flux, period * 2.0 / 3.0, first, last);
    if (faster.salience > best.salience) best = faster;
  }
  // Then the octave, as estimate_tempo decides it: the slowest level whose off-beats are
  // clearly weaker than its beats, or the one nearest the hint.
  std::vector<double> octaves;
  for (double ratio : {2.0, 1.0, 0.5}) {
    if (!in_range(best.period * ratio, frame_rate)) continue;
    octaves.push_back(ratio == 1.0 ? best.period
                                   : steady_grid(flux, best.period * ratio, first, last).period);
  }
  if (octaves.empty()) return best;
  if (hint_period) {
    LevelScore chosen = best;
    double nearest = std::numeric_limits<double>::infinity();
    for (double p : octaves) {
      const double distance = std::abs(std::log(p / *hint_period));
      if (distance < nearest) {
        nearest = distance;
        chosen.period = p;
      }
    }
    return chosen;
  }
  for (double p : octaves) {
    const double ratio =
        0.5 * (offbeat_ratio(flux, p, frame_rate) + offbeat_ratio(low, p, frame_rate));
    if (ratio < 0.55) return {p, best.salience};
  }
  return best;
}

}  // namespace seqc::music
