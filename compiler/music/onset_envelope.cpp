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

OnsetEnvelope onset_envelope(const AnalysisSignal& signal) {
  OnsetEnvelope env;
  // About 46 ms windows every 11.6 ms at 11 kHz: the resolution tempo and tracking need; the
  // fine envelope places each beat more precisely afterwards.
  env.window = signal.sample_rate >= 8000 ? 512 : 256;
  env.hop = env.window / 4;
  env.frame_rate = signal.sample_rate / double(env.hop);
  const std::size_t n = signal.samples.size();
  const std::size_t frames = n / env.hop + 1;
  const std::size_t bins = env.window / 2 + 1;
  const double bin_hz = signal.sample_rate / double(env.window);
  const auto low_bins = static_cast<std::size_t>(std::ceil(200.0 / bin_hz));
  Fft fft(env.window);
  std::vector<double> hann(env.window);
  for (std::size_t i = 0; i < env.window; ++i) {
    hann[i] = 0.5 - 0.5 * std::cos(2.0 * std::numbers::pi * double(i) / double(env.window));
  }
  std::vector<double> frame(env.window), mags, prev(bins, 0.0), cur(bins);
  std::vector<double> raw(frames, 0.0);
  env.low.assign(frames, 0.0);
  for (std::size_t f = 0; f < frames; ++f) {
    const auto start = static_cast<long long>(f * env.hop) - static_cast<long long>(env.window / 2);
    for (std::size_t i = 0; i < env.window; ++i) {
      const long long s = start + static_cast<long long>(i);
      frame[i] = (s >= 0 && s < static_cast<long long>(n))
                     ? signal.samples[static_cast<std::size_t>(s)] * hann[i]
                     : 0.0;
    }
    fft.magnitudes(frame, mags);
    double flux = 0, low = 0;
    for (std::size_t k = 1; k < bins; ++k) {
      // Log compression: a quiet intro's onsets count nearly as much as the chorus's.
      cur[k] = std::log1p(100.0 * mags[k]);
      const double rise = std::max(0.0, cur[k] - prev[k]);
      flux += rise;
      if (k <= low_bins) low += rise;
    }
    if (f > 0) {
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
