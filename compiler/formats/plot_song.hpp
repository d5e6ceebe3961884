// The song under a plot's lanes (`seqc plot` of a file with `music:`): the audio's waveform on
// the sequence's time axis and the beats found in it, drawn in a lane of its own with the file's
// bar grid over it, so a tempo map that drifts from the music shows as detected beats sliding
// off the grid lines.
//
// Time: the sequence's time t (ms) is the audio's time downbeat_s + t / 1000, as the `music:`
// block's downbeat says. Each pixel column of the lane shows the largest |sample| of the audio
// that falls in that column's time span, as a vertical bar about the lane's middle whose height
// is that peak times the lane's height (a full-scale click fills the lane); silence and time
// outside the audio draw nothing. Each detected beat inside the window is a red tick across the
// lane's top quarter.
#pragma once

#include <string>
#include <vector>

#include "compiler/formats/plot_axes.hpp"

namespace seqc::compiler {

struct PlotSong {
  std::string label;           // the audio file's name, shown beside the lane
  std::vector<float> samples;  // mono, in [-1, 1]
  double sample_rate = 0;
  double downbeat_s = 0;        // where the sequence's time 0 falls in the audio
  std::vector<double> beats_s;  // beats found in the audio, in audio seconds
};

namespace plot {

inline constexpr double kSongLane = 72;

// The lane's picture from y0 to y0 + kSongLane (label, frame, waveform, beat ticks).
std::string song_lane(const PlotSong& song, const Frame& f, double y0);

}  // namespace plot
}  // namespace seqc::compiler
