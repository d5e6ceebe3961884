// The smallest dance set to a song, shared by the tests of starting on a downbeat: two beats at
// 120 bpm (1 s) moving the base, the song `song.wav` with its downbeat at 0.750 s.
#pragma once

namespace seqc::cli::test {

constexpr const char* kTwoBeatSongDance =
    "robot: xarm\n"
    "music:\n"
    "  file: song.wav\n"
    "  downbeat: 0.750s\n"
    "  tempo: 120\n"
    "  meter: 4/4\n"
    "sequence:\n"
    "  - move: {base: 400}\n"
    "    time: 1b\n"
    "  - move: {base: 600}\n"
    "    time: 1b\n";

}  // namespace seqc::cli::test
