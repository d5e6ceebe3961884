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

// One evenly spaced grid for the whole song: beat k at phase + k * period (frames). Music played
// to a click keeps one grid through its breaks, fills and passages where the off-beats are as
// loud as the beats, where a tracker that looks a few beats around it can slip half a beat.
struct SteadyGrid {
  double period = 0;  // frames per beat
  double phase = 0;   // frames, in [0, period)
};
// The grid, within 3 % of `period`, whose beats fall on the most onset strength over the frames
// from `first` to `last` (each grid beat takes the envelope's largest value within a frame).
// Its period is resolved until the grid's last beat moves less than half a frame.
SteadyGrid steady_grid(const std::vector<double>& flux, double period, std::size_t first,
                       std::size_t last);

// The share of `frames` with an onset at them: the envelope at least its RMS within a frame.
double onset_share(const std::vector<double>& flux, const std::vector<double>& frames);

// The beats of `grid` from frame `first` to `last`, rounded to no frame.
std::vector<double> grid_frames(const SteadyGrid& grid, double first, double last);

// The beat among the metrical levels around `period`, each on its own steady grid over frames
// `first` to `last`: the family (the level, or the one at two thirds of its period when that
// one's grid is more strongly marked) and then the octave: the slowest of half, the level
// and double whose off-beats are clearly weaker than its beats, or the one nearest
// `hint_period`.
// How strongly a level's steady grid is marked (its salience): the envelope's mean at its beats
// (each the largest value within a frame) over its mean over the span. A grid at two thirds or
// three halves of the beat lands on the beats only every other time and scores lower than the
// beat; on noise every level scores about 1.3, on music with a beat 1.8 or more.
struct LevelScore {
  double period = 0;
  double salience = 0;
};
LevelScore score_level(const std::vector<double>& flux, double period, std::size_t first,
                       std::size_t last);
LevelScore choose_level(const std::vector<double>& flux, const std::vector<double>& low,
                        double frame_rate, double period, std::size_t first, std::size_t last,
                        std::optional<double> hint_period);

}  // namespace seqc::music
