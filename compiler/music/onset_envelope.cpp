#include "compiler/music/onset_envelope.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "compiler/music/fft.hpp"

namespace seqc::music {

AnalysisSignal reduce_for_analysis(std::span<const float> samples, double sample_rate) {
  // An integer factor keeps sample times exact multiples; averaging is a crude low-pass, but
  // aliased cymbals still read as onsets, which is all the envelope needs.
  const auto factor = static_cast<std::size_t>(std::max(1.0, std::floor(sample_rate / 11025.0)));
  AnalysisSignal out;
  out.sample_rate = sample_rate / double(factor);
  out.samples.resize(samples.size() / factor);
  for (std::size_t i = 0; i < out.samples.size(); ++i) {
    double sum = 0;
    for (std::size_t k = 0; k < factor; ++k) sum += samples[i * factor + k];
    out.samples[i] = sum / double(factor);
  }
  return out;
}

namespace {

// Third-octave bands from about 40 Hz up: each FFT bin's band, so a band's energy is the mean
// of its bins. Equal weight per band keeps the many high bins from drowning the kick and the
// bass, which carry the beat in most music.
std::vector<std::size_t> band_of_bins(std::size_t bins, double bin_hz, std::size_t& bands) {
  std::vector<std::size_t> band(bins, 0);
  bands = 0;
  for (std::size_t k = 1; k < bins; ++k) {
    const double hz = std::max(40.0, double(k) * bin_hz);
    band[k] = static_cast<std::size_t>(std::floor(3.0 * std::log2(hz / 40.0)));
    bands = std::max(bands, band[k] + 1);
  }
  return band;
}

// Log band energies of the window of `signal` centred on `centre` (zeros past the ends).
void band_levels(const AnalysisSignal& signal, long long centre, const std::vector<double>& window,
                 const Fft& fft, const std::vector<std::size_t>& band, std::size_t bands,
                 std::vector<double>& frame, std::vector<double>& mags, std::vector<double>& out) {
  const std::size_t size = window.size();
  const long long start = centre - static_cast<long long>(size / 2);
  const auto n = static_cast<long long>(signal.samples.size());
  for (std::size_t i = 0; i < size; ++i) {
    const long long s = start + static_cast<long long>(i);
    frame[i] = (s >= 0 && s < n) ? signal.samples[static_cast<std::size_t>(s)] * window[i] : 0.0;
  }
  fft.magnitudes(frame, mags);
  out.assign(bands, 0.0);
  std::vector<int> count(bands, 0);
  for (std::size_t k = 1; k < mags.size(); ++k) {
    out[band[k]] += mags[k] * mags[k];
    ++count[band[k]];
  }
  // Log compression: a quiet intro's onsets count nearly as much as the chorus's.
  // Scaled by the window's size, so the fine flux's short windows read the same levels.
  const double scale = 51200.0 / double(size);
  for (std::size_t b = 0; b < bands; ++b) {
    out[b] = count[b] > 0 ? std::log1p(scale * std::sqrt(out[b] / count[b])) : 0.0;
  }
}

std::vector<double> hann(std::size_t size) {
  std::vector<double> w(size);
  for (std::size_t i = 0; i < size; ++i) {
    w[i] = 0.5 - 0.5 * std::cos(2.0 * std::numbers::pi * double(i) / double(size));
  }
  return w;
}

}  // namespace

OnsetEnvelope onset_envelope(const AnalysisSignal& signal) {
  OnsetEnvelope env;
  // About 46 ms windows every 11.6 ms at 11 kHz: the resolution tempo and tracking need; the
  // fine flux places each beat more precisely afterwards.
  env.window = signal.sample_rate >= 8000 ? 512 : 256;
  env.hop = env.window / 4;
  env.frame_rate = signal.sample_rate / double(env.hop);
  const std::size_t n = signal.samples.size();
  const std::size_t frames = n / env.hop + 1;
  const std::size_t bins = env.window / 2 + 1;
  const double bin_hz = signal.sample_rate / double(env.window);
  std::size_t bands = 0;
  const std::vector<std::size_t> band = band_of_bins(bins, bin_hz, bands);
  // Bands wholly below 200 Hz: kicks and bass notes, which mark bar lines in most music.
  const auto low_bands = static_cast<std::size_t>(std::floor(3.0 * std::log2(200.0 / 40.0)));
  std::vector<int> pitch_class(bins, -1);
  for (std::size_t k = 1; k < bins; ++k) {
    const double hz = double(k) * bin_hz;
    if (hz < 200 || hz > 2000) continue;
    const long semitones = std::lround(12.0 * std::log2(hz / 440.0));
    pitch_class[k] = static_cast<int>(((semitones % 12) + 12) % 12);
  }
  Fft fft(env.window);
  const std::vector<double> window = hann(env.window);
  std::vector<double> frame(env.window), mags, prev, cur;
  std::vector<double> raw(frames, 0.0);
  env.low.assign(frames, 0.0);
  env.chroma.assign(frames, {});
  env.levels.assign(frames, {});
  for (std::size_t f = 0; f < frames; ++f) {
    band_levels(signal, static_cast<long long>(f * env.hop), window, fft, band, bands, frame, mags,
                cur);
    double total = 0;
    for (std::size_t k = 1; k < mags.size(); ++k) {
      if (pitch_class[k] < 0) continue;
      env.chroma[f][static_cast<std::size_t>(pitch_class[k])] += float(mags[k] * mags[k]);
      total += mags[k] * mags[k];
    }
    if (total > 0) {
      for (float& c : env.chroma[f]) c = float(c / total);
    }
    env.levels[f].assign(cur.begin(), cur.end());
    if (f > 0) {
      double flux = 0, low = 0;
      for (std::size_t b = 0; b < bands; ++b) {
        const double rise = std::max(0.0, cur[b] - prev[b]);
        flux += rise;
        if (b < low_bands) low += rise;
      }
      raw[f] = flux;
      env.low[f] = low;
    }
    std::swap(prev, cur);
  }
  // Remove the local mean (about 0.4 s): sustained noise and dense textures lift the flux
  // without being onsets.
  const auto half = static_cast<std::size_t>(std::lround(0.2 * env.frame_rate));
  std::vector<double> prefix(frames + 1, 0.0);
  for (std::size_t f = 0; f < frames; ++f) prefix[f + 1] = prefix[f] + raw[f];
  env.flux.assign(frames, 0.0);
  double sum_sq = 0;
  for (std::size_t f = 0; f < frames; ++f) {
    const std::size_t lo = f > half ? f - half : 0;
    const std::size_t hi = std::min(frames, f + half + 1);
    const double mean = (prefix[hi] - prefix[lo]) / double(hi - lo);
    env.flux[f] = std::max(0.0, raw[f] - mean);
    sum_sq += env.flux[f] * env.flux[f];
  }
  const double rms = std::sqrt(sum_sq / double(std::max<std::size_t>(frames, 1)));
  if (rms > 0) {
    for (double& v : env.flux) v /= rms;
  }
  return env;
}

FinePeak fine_flux_peak(const AnalysisSignal& signal, double from_s, double to_s) {
  constexpr std::size_t kWindow = 64, kHop = 8;
  const auto first = static_cast<long long>(std::floor(from_s * signal.sample_rate));
  const auto last = static_cast<long long>(std::ceil(to_s * signal.sample_rate));
  const auto n = static_cast<long long>(signal.samples.size());
  if (last <= 0 || first >= n || last <= first) return {};
  std::size_t bands = 0;
  const std::vector<std::size_t> band =
      band_of_bins(kWindow / 2 + 1, signal.sample_rate / double(kWindow), bands);
  const Fft fft(kWindow);
  const std::vector<double> window = hann(kWindow);
  std::vector<double> frame(kWindow), mags, prev, cur, flux;
  // The window before `first` is the first frame's reference.
  for (long long c = first - static_cast<long long>(kHop); c <= last; c += kHop) {
    band_levels(signal, c, window, fft, band, bands, frame, mags, cur);
    if (!prev.empty()) {
      double rise = 0;
      for (std::size_t b = 0; b < bands; ++b) rise += std::max(0.0, cur[b] - prev[b]);
      flux.push_back(rise);
    }
    std::swap(prev, cur);
  }
  std::size_t best = 0;
  for (std::size_t i = 1; i < flux.size(); ++i) {
    if (flux[i] > flux[best]) best = i;
  }
  double offset = 0;
  if (best > 0 && best + 1 < flux.size()) {
    const double a = flux[best - 1], b = flux[best], c = flux[best + 1];
    const double denom = a - 2 * b + c;
    if (denom < 0) offset = std::clamp(0.5 * (a - c) / denom, -0.5, 0.5);
  }
  // Flux i compares the window centred half a hop before sample first + i * hop with the one
  // before it: the rise happened between the two centres.
  const double sample = double(first) + (double(best) + offset - 0.5) * double(kHop);
  return {sample / signal.sample_rate, flux.empty() ? 0.0 : flux[best]};
}

FineEnvelope fine_envelope(const AnalysisSignal& signal) {
  FineEnvelope fine;
  fine.block = std::max<std::size_t>(1, static_cast<std::size_t>(signal.sample_rate / 2000.0));
  fine.block_rate = signal.sample_rate / double(fine.block);
  const std::size_t blocks = signal.samples.size() / fine.block;
  fine.amplitude.resize(blocks);
  // Of the first difference: a bass note's waveform swells and fades every half cycle (9 ms at
  // 55 Hz), which would read as onsets; the difference keeps the attacks (clicks, noise, the
  // top of a kick) and leaves a tenth or less of anything below 200 Hz.
  for (std::size_t b = 0; b < blocks; ++b) {
    double sum = 0;
    for (std::size_t i = 0; i < fine.block; ++i) {
      const std::size_t at = b * fine.block + i;
      const double s = signal.samples[at] - (at > 0 ? signal.samples[at - 1] : 0.0);
      sum += s * s;
    }
    fine.amplitude[b] = std::sqrt(sum / double(fine.block));
  }
  return fine;
}

}  // namespace seqc::music
