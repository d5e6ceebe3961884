// Test songs made from decaying sines and noise (kick, snare, hi-hat, a bass note per bar), so
// every expectation comes from how the song was made: its tempo, meter, where bar 1 beat 1 is,
// where the tempo changes. Deterministic for a seed (its own normal deviates from mt19937, whose
// output the standard fixes).
#pragma once

#include <optional>
#include <vector>

namespace seqc::testing {

struct SongSpec {
  double sample_rate = 22050;
  double tempo = 120;
  // Beats per bar: 4 (kick 1 and 3, snare 2 and 4), 2 (kick 1, snare 2), 3 or 6 (kick on 1,
  // soft snares on the others).
  int meter = 4;
  double third_kick = 0.6;  // 4/4: the kick on beat 3, against 1 on beat 1
  double lead_in_s = 0.75;  // background noise only, before bar 1 beat 1
  int bars = 24;
  // From this bar (1-based) on, this tempo.
  std::optional<int> change_bar;
  double change_tempo = 0;
  // Each bar this much faster than the one before (BPM): a band speeding up without a click.
  double drift_per_bar = 0;
  double swing = 0;    // the off-beat eighth at (1 + swing) / 2 of the beat: 1/3 = triplet
  int quiet_bars = 0;  // the first bars at -20 dB (a quiet intro)
  // From this bar (1-based), this many bars of a skank: the off-beats loud (snare and open
  // hi-hat), the beats a soft hi-hat only, as in a breakdown.
  int skank_bar = 0;
  int skank_bars = 0;
  int pickup = 0;      // beats before bar 1 (an upbeat: snare and hi-hat), ending at it
  int late_beat = -1;  // this beat's hits (0-based, from bar 1) and late_count - 1 more
  int late_count = 1;  // come late_ms late
  double late_ms = 0;
  double jitter_ms = 0;  // standard deviation of each hit's timing
  double noise = 0.002;  // background noise, RMS
  bool bass = true;      // a bass note on every bar's first beat
  unsigned seed = 1;
};

struct Song {
  std::vector<float> samples;
  double sample_rate = 0;
  double downbeat_s = 0;        // bar 1 beat 1, as generated (= lead_in_s)
  std::vector<double> beats_s;  // every beat as planned, before jitter
  double duration_s() const { return double(samples.size()) / sample_rate; }
};

Song make_song(const SongSpec& spec);

// A click on every beat at `tempo` (1.5 kHz on the bar's first beat, 1 kHz elsewhere) after
// `lead_in_s` of silence, for `seconds`.
Song make_clicks(double tempo, int meter, double lead_in_s, double seconds, double sample_rate);

// Snare hits at `count` random times (uniform over the song): onsets without a pulse.
Song make_random_hits(double seconds, int count, double sample_rate, unsigned seed);

// White noise of the given RMS.
Song make_noise(double seconds, double rms, double sample_rate, unsigned seed);

}  // namespace seqc::testing
