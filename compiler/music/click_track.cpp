#include "compiler/music/click_track.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace seqc::music {

std::vector<float> mix_click_track(std::span<const float> song, double sample_rate,
                                   const TempoMap& map) {
  std::vector<float> out(song.size());
  for (std::size_t i = 0; i < song.size(); ++i) out[i] = 0.7f * song[i];
  const double duration = double(song.size()) / sample_rate;
  const auto length = static_cast<std::size_t>(0.03 * sample_rate);  // 30 ms, 5 ms decay
  for (const MapBeat& beat : map_beats(as_printed(map), 0.0, duration)) {
    const double freq = beat.downbeat ? 1500.0 : 1000.0;
    const double level = beat.downbeat ? 0.5 : 0.3;
    const auto start = static_cast<std::size_t>(std::lround(beat.time_s * sample_rate));
    for (std::size_t k = 0; k < length && start + k < out.size(); ++k) {
      const double t = double(k) / sample_rate;
      const double click =
          level * std::exp(-t / 0.005) * std::sin(2.0 * std::numbers::pi * freq * t);
      out[start + k] = static_cast<float>(std::clamp(double(out[start + k]) + click, -1.0, 1.0));
    }
  }
  return out;
}

}  // namespace seqc::music
