#include "tests/music/song_generator.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

namespace seqc::testing {
namespace {

constexpr double kPi = std::numbers::pi;

class Noise {
 public:
  explicit Noise(unsigned seed) : rng_(seed) {}
  double uniform() { return (double(rng_()) + 0.5) / 4294967296.0; }
  // Box-Muller on mt19937's fixed output: the same deviates on every standard library.
  double normal() {
    return std::sqrt(-2.0 * std::log(uniform())) * std::cos(2.0 * kPi * uniform());
  }

 private:
  std::mt19937 rng_;
};

void add(std::vector<double>& out, double sr, double at_s, double length_s, auto&& voice) {
  const auto start = static_cast<long long>(std::lround(at_s * sr));
  const auto n = static_cast<long long>(length_s * sr);
  for (long long k = 0; k < n; ++k) {
    const long long i = start + k;
    if (i < 0 || i >= static_cast<long long>(out.size())) continue;
    out[static_cast<std::size_t>(i)] += voice(double(k) / sr);
  }
}

// A kick: a sine falling from 150 Hz to 50 Hz, decaying over 120 ms, with a 2 ms click.
void kick(std::vector<double>& out, double sr, double at, double level, Noise& noise) {
  add(out, sr, at, 0.35, [&](double t) {
    const double phase = 2 * kPi * (50 * t + 100 * 0.03 * (1 - std::exp(-t / 0.03)));
    const double click = t < 0.002 ? 0.3 * noise.normal() : 0.0;
    return level * (0.8 * std::exp(-t / 0.12) * std::sin(phase) + click);
  });
}

void snare(std::vector<double>& out, double sr, double at, double level, Noise& noise) {
  add(out, sr, at, 0.25, [&](double t) {
    return level * (0.35 * std::exp(-t / 0.06) * noise.normal() +
                    0.3 * std::exp(-t / 0.05) * std::sin(2 * kPi * 180 * t));
  });
}

void hat(std::vector<double>& out, double sr, double at, double level, Noise& noise) {
  double previous = 0;
  add(out, sr, at, 0.06, [&](double t) {
    const double white = noise.normal();
    const double bright = white - previous;  // a first difference: mostly high frequencies
    previous = white;
    return level * 0.12 * std::exp(-t / 0.015) * bright;
  });
}

void bass_note(std::vector<double>& out, double sr, double at, double length, double freq,
               double level) {
  add(out, sr, at, length,
      [&](double t) { return level * 0.3 * std::exp(-t / 0.6) * std::sin(2 * kPi * freq * t); });
}

Song finish(std::vector<double>& mix, double sr) {
  Song song;
  song.sample_rate = sr;
  song.samples.resize(mix.size());
  for (std::size_t i = 0; i < mix.size(); ++i) {
    song.samples[i] = static_cast<float>(std::clamp(mix[i], -1.0, 1.0));
  }
  return song;
}

}  // namespace

Song make_song(const SongSpec& spec) {
  const double sr = spec.sample_rate;
  // Beat times first: bar by bar, each bar at its tempo.
  std::vector<double> beats;
  double t = spec.lead_in_s;
  for (int bar = 1; bar <= spec.bars; ++bar) {
    const double tempo =
        (spec.change_bar && bar >= *spec.change_bar ? spec.change_tempo : spec.tempo) +
        spec.drift_per_bar * (bar - 1);
    for (int b = 0; b < spec.meter; ++b) {
      beats.push_back(t);
      t += 60.0 / tempo;
    }
  }
  const double end = t + 1.0;
  std::vector<double> mix(static_cast<std::size_t>(end * sr), 0.0);
  Noise noise(spec.seed);
  for (double& s : mix) s = spec.noise * noise.normal();
  const double notes[] = {55.0, 65.41, 49.0, 58.27};  // A1 C2 G1 Bb1
  for (std::size_t i = 0; i < beats.size(); ++i) {
    const int bar = static_cast<int>(i) / spec.meter;
    const int beat = static_cast<int>(i) % spec.meter;
    const double level = bar < spec.quiet_bars ? 0.1 : 1.0;
    const double period = (i + 1 < beats.size() ? beats[i + 1] : t) - beats[i];
    const int index = static_cast<int>(i);
    const bool is_late = index >= spec.late_beat && index < spec.late_beat + spec.late_count;
    const double late = spec.late_beat >= 0 && is_late ? spec.late_ms * 1e-3 : 0.0;
    auto at = [&](double offset) {
      return beats[i] + late + offset * period + spec.jitter_ms * 1e-3 * noise.normal();
    };
    if (spec.skank_bars > 0 && bar + 1 >= spec.skank_bar &&
        bar + 1 < spec.skank_bar + spec.skank_bars) {
      hat(mix, sr, at(0), 0.3 * level, noise);
      snare(mix, sr, at(0.5), level, noise);
      hat(mix, sr, at(0.5), level, noise);
      continue;
    }
    if (beat == 0) {
      kick(mix, sr, at(0), level, noise);
      if (spec.bass) {
        bass_note(mix, sr, at(0), period * spec.meter, notes[bar % 4], level);
      }
    } else if (spec.meter == 4 && beat == 2) {
      kick(mix, sr, at(0), spec.third_kick * level, noise);
    } else if (spec.meter == 4 || spec.meter == 2) {
      snare(mix, sr, at(0), level, noise);
    } else {
      snare(mix, sr, at(0), 0.5 * level, noise);
    }
    hat(mix, sr, at(0), level, noise);
    hat(mix, sr, at((1 + spec.swing) / 2), 0.7 * level, noise);
  }
  for (int k = 1; k <= spec.pickup; ++k) {
    const double at = spec.lead_in_s - k * 60.0 / spec.tempo;
    snare(mix, sr, at, 1.0, noise);
    hat(mix, sr, at, 1.0, noise);
  }
  Song song = finish(mix, sr);
  song.downbeat_s = spec.lead_in_s;
  song.beats_s = beats;
  return song;
}

Song make_clicks(double tempo, int meter, double lead_in_s, double seconds, double sample_rate) {
  std::vector<double> mix(static_cast<std::size_t>(seconds * sample_rate), 0.0);
  Song song;
  for (int i = 0; lead_in_s + i * 60.0 / tempo < seconds - 0.1; ++i) {
    const double at = lead_in_s + i * 60.0 / tempo;
    const double freq = i % meter == 0 ? 1500.0 : 1000.0;
    const double level = i % meter == 0 ? 0.6 : 0.3;
    add(mix, sample_rate, at, 0.03,
        [&](double t) { return level * std::exp(-t / 0.005) * std::sin(2 * kPi * freq * t); });
    song.beats_s.push_back(at);
  }
  Song out = finish(mix, sample_rate);
  out.downbeat_s = lead_in_s;
  out.beats_s = song.beats_s;
  return out;
}

Song make_random_hits(double seconds, int count, double sample_rate, unsigned seed) {
  std::vector<double> mix(static_cast<std::size_t>(seconds * sample_rate), 0.0);
  Noise noise(seed);
  for (double& s : mix) s = 0.002 * noise.normal();
  for (int i = 0; i < count; ++i) snare(mix, sample_rate, noise.uniform() * seconds, 1.0, noise);
  return finish(mix, sample_rate);
}

Song make_noise(double seconds, double rms, double sample_rate, unsigned seed) {
  std::vector<double> mix(static_cast<std::size_t>(seconds * sample_rate));
  Noise noise(seed);
  for (double& s : mix) s = rms * noise.normal();
  return finish(mix, sample_rate);
}

}  // namespace seqc::testing
