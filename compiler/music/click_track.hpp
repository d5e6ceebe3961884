// The song with a click on every beat of a tempo map mixed in, for checking a map by ear: a
// short 1.5 kHz click on each bar's first beat, a softer 1 kHz one on the others. Pure.
#pragma once

#include <span>
#include <vector>

#include "compiler/music/tempo_map.hpp"

namespace seqc::music {

// Same length and rate as `song`; the song at 70% so the clicks fit without clipping, and the
// sum clamped to [-1, 1]. The clicks are on as_printed(map): the beats a file pasting the
// printed `music:` block counts, so what is heard is what `seqc check` will compare.
std::vector<float> mix_click_track(std::span<const float> song, double sample_rate,
                                   const TempoMap& map);

}  // namespace seqc::music
