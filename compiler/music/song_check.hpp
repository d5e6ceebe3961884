// Checks a choreography against its song's audio (the `music:` block): the file must decode,
// the dance should end before the song does, and the song's beats, as the beat analysis finds
// them (compiler/music), should fall where the file's tempo map puts them. Pure: the audio comes
// through a SongReader.
#pragma once

#include "base/source.hpp"
#include "compiler/frontend/reporter.hpp"
#include "compiler/timeline/exact_time.hpp"
#include "compiler/timeline/song.hpp"
#include "compiler/timeline/tempo_map.hpp"

namespace seqc::compiler {

// How far (ms) a detected beat may lie from the file's before the check warns.
inline constexpr double kSongBeatToleranceMs = 20;

// Reports an error at the `file:` value when the song cannot be decoded; a warning when the
// dance (ending at `end`, program time) runs past the end of the audio; and, from the first bar
// whose detected beats lie more than kSongBeatToleranceMs from the file's (by their median) for
// two bars or more, one of two warnings at the `music:` key, each with a note giving the line
// to paste. When the offsets grow along a line (a line through them explains them, and drifts by
// more than the tolerance): "the song runs at 96.0 bpm; the file says 96.5 (from bar 3 its
// beats run ahead by 26 ms, growing to 152 ms)" with `tempo: 96` (or "from bar 9 the song runs
// ..." with the `changes:` entry), and nothing after it, since the later bars follow from it.
// Otherwise "the file's beats run 40 ms ahead of the song from bar 3" (or "behind"), with
// `downbeat: 0.790s` when that is from the first bar with beats.
void check_song(const Song& song, const TempoMap& map, ExactMs end, SongReader& reader,
                Reporter& reporter);

// Only the first of those: an error at `file.at` when the song cannot be decoded, for a file whose
// `music:` block or steps have mistakes (there is no tempo map or dance to compare then).
void check_song_readable(const SongFile& file, SongReader& reader, Reporter& reporter);

}  // namespace seqc::compiler
