// What the beat analysis reads from the samples: the onset-strength envelope (spectral flux of
// log band energies over third-octave bands, all bands and the low band apart) and each frame's
// pitch classes on a frame grid, a fine amplitude envelope, and a fine spectral flux around a
// given instant, for placing onsets to a fraction of a millisecond. Pure functions of the
// samples.
#pragma once

#include <array>
#include <cstddef>
#include <span>
#include <vector>

namespace seqc::music {

// The samples the analysis works on: the input reduced to about 11 kHz (an integer factor, each
// output sample the mean of `factor` input samples), enough for every onset a beat is made of.
struct AnalysisSignal {
  std::vector<double> samples;
  double sample_rate = 0;  // of `samples`
};
AnalysisSignal reduce_for_analysis(std::span<const float> samples, double sample_rate);

// Frame f is centred on sample f * hop of the analysis signal (frames reach past the ends with
// zeros). flux[f] >= 0 rises where energy appears; low[f] is the same below 200 Hz, where kicks
// and bass notes (which mark bar lines in most music) live.
struct OnsetEnvelope {
  std::vector<double> flux;  // high-passed (local mean removed), half-wave rectified, unit std
  std::vector<double> low;   // low-band flux, not normalised
  // The energy of each pitch class (200 Hz - 2 kHz, where chords are), summed to 1 per frame:
  // a chord change moves it, a drum hit barely does.
  std::vector<std::array<float, 12>> chroma;
  // Each frame's log energy per third-octave band (the same levels the flux differences): where
  // instruments enter or leave, which in most music is on a bar line, these change.
  std::vector<std::vector<float>> levels;
  std::size_t hop = 0;     // analysis samples per frame
  std::size_t window = 0;  // analysis samples per FFT
  double frame_rate = 0;   // frames per second
};
OnsetEnvelope onset_envelope(const AnalysisSignal& signal);

// RMS amplitude of the first difference of the analysis samples, in consecutive blocks of
// `block` samples (about 0.5 ms each).
struct FineEnvelope {
  std::vector<double> amplitude;
  std::size_t block = 0;
  double block_rate = 0;  // blocks per second
};
FineEnvelope fine_envelope(const AnalysisSignal& signal);

// The same band flux as the envelope's, on 64-sample windows every 8 samples (0.7 ms at
// 11 kHz), from `from_s` to `to_s`: the instant of its largest value (refined by a parabola) and
// that value, or a negative time when the span is outside the signal. Computed only around
// beats, so its cost grows with the beats, not with the song's length.
struct FinePeak {
  double time_s = -1;
  double strength = 0;
};
FinePeak fine_flux_peak(const AnalysisSignal& signal, double from_s, double to_s);

}  // namespace seqc::music
