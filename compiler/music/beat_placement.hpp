// Each tracked beat placed on its onset, and the cues that tell a bar's first beat (the change
// of harmony and of sound at each beat), from the analysis signal and its envelopes
// (onset_envelope.hpp). Pure functions; beat_analysis.cpp runs them in order.
#pragma once

#include <vector>

#include "compiler/music/onset_envelope.hpp"

namespace seqc::music {

struct Beat {
  double frame = 0;        // where the tracker put it, in envelope frames
  double time_s = 0;       // the onset, or the tracker's frame when there is none
  bool has_onset = false;  // a clear onset near the tracked frame
  bool fine = false;       // placed on the amplitude envelope (a hit standing out of silence)
  double rise = 0;         // how much the amplitude rose at the onset
  double strength = 0;     // the onset envelope's peak near the beat (unit: its RMS)
  double accent = 0;       // how strongly the beat is marked (bar lines are, in most music)
  double texture = 0;      // how much the sound changes there, over its mean: picks the phase
};

// The tracker's beat frames with the beats it skipped put back: an interval of about k periods
// holds k - 1 beats evenly spaced, so every beat's index counts whole beats from the first.
std::vector<double> whole_beats(const std::vector<int>& frames, const std::vector<double>& periods);

// Each beat on its onset (the amplitude rise where a hit stands out, else the fine band flux,
// moved by the median difference between the two), with its strength; has_onset false where
// there is no clear onset near it.
std::vector<Beat> place_beats(const std::vector<double>& frames, const std::vector<double>& periods,
                              const OnsetEnvelope& env, const FineEnvelope& fine,
                              const AnalysisSignal& signal);

// How much the harmony changes at each beat, 0 (the same chord) towards 1 (a new one).
std::vector<double> chord_changes(const std::vector<Beat>& beats, const OnsetEnvelope& env);

// How much the sound (the band levels) changes at each beat, over `per_bar` beats either side.
std::vector<double> texture_changes(const std::vector<Beat>& beats, const OnsetEnvelope& env,
                                    int per_bar);

}  // namespace seqc::music
