// A song's beats and tempo map from its samples (mono, any sample rate): band-flux onset
// envelope -> tempo and metrical level -> beat tracking, or one steady grid for music played to
// a click -> each beat placed on its onset -> meter and downbeat -> stretches of steady tempo,
// a least-squares line each, read as one chain. Pure: no files, no clocks. `seqc beats` prints
// the result (docs/music.md, How it listens).
//
// Refused as "no steady beat": a pulse that stands out of the music no more than a grid laid
// over noise does (salience under 1.5), or a confidence under 0.35. Confidence (0-1): the
// fraction of the map's beats, between the first and the last beat that has an onset, that have
// an onset within a tenth of a beat of where the map puts them. A drum machine scores above 0.9,
// a band in a dense mix 0.5-0.9.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

#include "base/result.hpp"
#include "compiler/music/tempo_map.hpp"

namespace seqc::music {

struct BeatOptions {
  std::optional<Meter> meter;        // given: no meter detection
  std::optional<double> tempo_hint;  // BPM: picks between half, detected and double tempo
};

struct BeatAnalysis {
  TempoMap map;
  double confidence = 0;
  // The onsets' median distance from where the map puts their beats, in seconds.
  double spread_s = 0;
  // The tracked beats from the first onset to the last, each on its onset where it has one.
  std::vector<double> beats_s;
  // Each of those beats' place in its bar, 1 (the bar's first beat) to the meter's beats.
  std::vector<int> positions;
  bool meter_detected = false;  // false when BeatOptions::meter gave it
};

// The analysis, or an Error whose message says why no tempo map can be given (too short, no
// steady beat), worded for "seqc: error: SONG: <message>".
Result<BeatAnalysis> analyze_beats(std::span<const float> samples, double sample_rate,
                                   const BeatOptions& options);

// The tracked beats, one per line: the time in seconds to the millisecond, a tab, the place in
// the bar ("12.500\t1"), the layout of the beat annotations that evaluation tools read.
std::string beat_list(const BeatAnalysis& analysis);

// "163 beats, confidence 0.97 (the share of the map's beats with an onset within a tenth of a
// beat)".
std::string analysis_summary(const BeatAnalysis& analysis);

}  // namespace seqc::music
