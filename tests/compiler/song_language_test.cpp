// The `music:` block: the song's tempo map owns every beat and bar of the file, time 0 of the
// sequence is the song's downbeat, and the block's mistakes are located. Expected times are
// worked out by hand from docs/language.md ("Music").
#include <gtest/gtest.h>

#include "tests/compiler/lang_test_util.hpp"

namespace seqc::compiler {
namespace {

using testing::compile_text;
using testing::diagnostics_of;
using testing::MemoryFiles;
using testing::messages;
using testing::program_of;

constexpr const char* kSong = R"(robot: xarm
music:
  file: song.wav
  downbeat: 0.5s
  tempo: 120
  meter: 4/4
  changes:
    - {bar: 3, tempo: 60}
)";

TEST(Song, BarsAndBeatsFollowTheSongsChangesAndTimeZeroIsTheDownbeat) {
  auto out = compile_text(std::string(kSong) + R"(sequence:
  - move: home
    time: 1s
  - move: {base: 700}
    at: bar 4
    time: 2b
  - move: {base: 600}
    time: 1bar
)");
  const ServoProgram& p = program_of(out);
  // Bars 1-2 at 120 bpm: 8 beats x 0.5 s = 4 s; bar 3 at 60 bpm: 4 beats x 1 s = 4 s, so bar 4
  // starts 8 s after the downbeat. 2 beats there last 2 s, a bar 4 s.
  ASSERT_EQ(p.keyframes.size(), 4u);       // home, the hold until bar 4, the two moves
  EXPECT_EQ(p.keyframes[0].start_ms, 0u);  // the first step starts on the downbeat
  EXPECT_EQ(p.keyframes[2].start_ms, 8000u);
  EXPECT_EQ(p.keyframes[2].time_ms, 2000);
  EXPECT_EQ(p.keyframes[3].start_ms, 10000u);
  EXPECT_EQ(p.keyframes[3].time_ms, 4000);
  // The program carries the song for later stages: the file beside the choreography, and the
  // downbeat (program time 0) at 500 ms into the audio.
  ASSERT_TRUE(p.timeline.song.has_value());
  EXPECT_EQ(p.timeline.song->file, "song.wav");
  EXPECT_EQ(p.timeline.song->downbeat, ExactMs(500));
}

TEST(Song, TheSongFileIsResolvedRelativeToTheChoreography) {
  MemoryFiles files;
  files.files["dances/main.yaml"] = R"(robot: xarm
music: {file: ../music/song.ogg, tempo: 128, meter: 4/4}
sequence:
  - move: home
    time: 1b
)";
  auto out = compile_file("dances/main.yaml", files, CompileOptions{});
  const ServoProgram& p = program_of(out);
  ASSERT_TRUE(p.timeline.song.has_value());
  EXPECT_EQ(p.timeline.song->file, "music/song.ogg");
  EXPECT_EQ(p.timeline.song->downbeat, ExactMs(0));  // no downbeat: the audio's start
  // One beat at 128 bpm: 60000 / 128 = 468.75 ms, sent as 469.
  EXPECT_EQ(p.keyframes[0].time_ms, 469);
}

TEST(Song, AMeterChangeCountsBarsFromItsBarLine) {
  auto out = compile_text(R"(robot: xarm
music:
  file: song.wav
  tempo: 60
  meter: 4/4
  changes:
    - {bar: 2, meter: 3/4}
sequence:
  - move: home
    time: 1s
  - move: {base: 700}
    at: bar 3 beat 2
    time: 1s
)");
  const ServoProgram& p = program_of(out);
  // Bar 1: 4 beats (4 s); bar 2: 3 beats (3 s); bar 3 beat 2 is 1 s later: 8 s.
  ASSERT_EQ(p.keyframes.size(), 3u);
  EXPECT_EQ(p.keyframes[2].start_ms, 8000u);
}

TEST(Song, ATempoOrMeterBesideTheSongPointsAtTheMusicBlock) {
  auto out = compile_text(std::string(kSong) + R"(tempo: 100
sequence:
  - move: home
    time: 1s
  - meter: 3/4
)");
  EXPECT_EQ(messages(out),
            (std::vector<std::string>{
                "9:8 error: 'tempo' beside 'music': the song sets the tempo at bar 1",
                "2:1 note: set it here, and changes by bar in its 'changes'",
                "13:12 error: 'meter: 3/4' while the song plays: its tempo map is the only one",
                "2:1 note: the song's 'music' sets tempo and meter, with changes by bar in its "
                "'changes'",
            }));
}

TEST(Song, AMalformedBlockIsLocated) {
  auto out = compile_text(R"(robot: xarm
music:
  file: song.wav
  dowbeat: 0.5s
  tempo: 120
  meter: 4
  changes:
    - {bar: 9, tempo: 132}
    - {bar: 5.5, tempo: 100}
    - {bar: 9, meter: 3/4}
sequence:
  - move: home
    time: 1s
)");
  // The value of 'bar' starts at column 13: four spaces, "- {bar: ".
  EXPECT_EQ(diagnostics_of(out),
            "main.yaml:4:3: error: unknown key 'dowbeat' in 'music'; did you mean 'downbeat'?\n"
            "    4 |   dowbeat: 0.5s\n"
            "      |   ^\n"
            "main.yaml:6:10: error: 'meter' must be beats per bar over the beat's note value, "
            "e.g. 'meter: 3/4' or 'meter: 6/8'\n"
            "    6 |   meter: 4\n"
            "      |          ^\n"
            "main.yaml:9:13: error: a change falls on a bar line: 'bar' must be a whole bar "
            "after bar 1, e.g. 'bar: 33'\n"
            "    9 |     - {bar: 5.5, tempo: 100}\n"
            "      |             ^\n"
            "main.yaml:10:13: error: the changes go by bar: bar 9 comes after bar 9\n"
            "   10 |     - {bar: 9, meter: 3/4}\n"
            "      |             ^\n");
}

TEST(Song, IncludedFilesBringNoSongAndNoTempoWhileOnePlays) {
  MemoryFiles files;
  files.files["main.yaml"] = std::string(kSong) + R"(sequence:
  - include: part.yaml
)";
  files.files["part.yaml"] = R"(robot: xarm
music: {file: other.wav, tempo: 90, meter: 4/4}
sequence:
  - move: home
    time: 1b
)";
  auto out = compile_file("main.yaml", files, CompileOptions{});
  const std::vector<std::string> m = messages(out);
  ASSERT_FALSE(m.empty());
  EXPECT_EQ(m[0],
            "2:1 error: 'music' belongs in the main file: the song plays from its first step");
}

}  // namespace
}  // namespace seqc::compiler
