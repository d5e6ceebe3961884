// Tempo estimation and beat tracking on an onset envelope (onset_envelope.hpp), in frames.
// Tempo: the autocorrelation of the envelope, weighted towards 120 BPM, gives a beat period; its
// half and double are the other metrical levels, and the beat is the slowest level whose
// off-beats (half a period after each beat) are clearly weaker than its beats, or the level
// nearest a hint. Tracking: dynamic programming (Ellis 2007): each frame's best score is its
// onset strength plus the best earlier beat's score, penalised by how far the interval strays
// from the local period (log ratio squared), so the beats follow gradual and sudden tempo
// changes within about a third of the period.
#pragma once

#include <optional>
#include <vector>

namespace seqc::music {

struct TempoEstimate {
  double period = 0;    // frames per beat, fractional
  double strength = 0;  // autocorrelation at that lag over that at lag 0 (0-1)
};

// The beat period, or nullopt when the envelope has no periodicity between 40 and 240 BPM.
// `hint_period` (frames) picks among the half, the period and its double.
std::optional<TempoEstimate> estimate_tempo(const std::vector<double>& flux,
                                            const std::vector<double>& low, double frame_rate,
                                            std::optional<double> hint_period);

// The local beat period at every frame: the autocorrelation peak of an 8 s window between 0.75
// and 1.3 times `period` (a change from 120 to 96 BPM is followed; the half and the double are
// not reached), so a tempo change moves the tracker's expectation with it.
std::vector<double> local_periods(const std::vector<double>& flux, double frame_rate,
                                  double period);

// Beat frames, ascending, from the first to the last frame the song has onsets in.
std::vector<int> track_beats(const std::vector<double>& flux, const std::vector<double>& periods);

}  // namespace seqc::music
