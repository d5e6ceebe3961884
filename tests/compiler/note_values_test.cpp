// Note values in the language: exact fractions of a beat or bar (1/3b, 1/6bar), meter changes
// that keep each note's length, tempos that name their note (3/8 = 60, dotted quarter = 60),
// and an included file's own tempo giving way to a song. Every expected time is worked out by
// hand in the comments: at 90 bpm a quarter is 2000/3 ms, so a 3/4 bar is 2000 ms; in 6/8 the
// eighth keeps its 1000/3 ms (180 bpm) and a bar of six is 2000 ms too.
#include <gtest/gtest.h>

#include "tests/compiler/lang_test_util.hpp"

namespace seqc::compiler {
namespace {

using testing::compile_text;
using testing::diagnostics_of;
using testing::MemoryFiles;
using testing::messages;
using testing::program_of;

// The start of each keyframe, in ms.
std::vector<std::uint32_t> starts(const ServoProgram& p) {
  std::vector<std::uint32_t> out;
  for (const auto& k : p.keyframes) out.push_back(k.start_ms);
  return out;
}

TEST(NoteValues, TwelveThirdsOfABeatEndExactlyOnBeatFour) {
  std::string text = "robot: xarm\ntempo: 120\nsequence:\n";
  for (int i = 0; i < 12; ++i) {
    text += "  - move: {base: " + std::to_string(i % 2 == 0 ? 600 : 650) + "}\n    time: 1/3b\n";
  }
  text += "  - move: {base: 500}\n    time: 1b\n";
  auto out = compile_text(text);
  const ServoProgram& p = program_of(out);
  // A beat is 500 ms, a third 500/3: step k starts at k x 500/3 ms, rounded once; the 13th
  // starts after 12 thirds = 4 beats = 2000 ms exactly.
  ASSERT_EQ(p.keyframes.size(), 13u) << diagnostics_of(out);
  EXPECT_EQ(p.keyframes[1].start_ms, 167u);  // 166.67
  EXPECT_EQ(p.keyframes[2].start_ms, 333u);  // 333.33
  EXPECT_EQ(p.keyframes[3].start_ms, 500u);  // exactly one beat
  EXPECT_EQ(p.keyframes[12].start_ms, 2000u);
}

TEST(NoteValues, SixthsOfABarAddUpToTheBar) {
  std::string text = "robot: xarm\ntempo: 120\nmeter: 4/4\nsequence:\n";
  for (int i = 0; i < 6; ++i)
    // Back and forth, so every step's end is a turn and stays an action boundary.
    text += "  - move: {base: " + std::string(i % 2 == 0 ? "600" : "650") +
            "}\n    time: 1/6bar\n";
  text += "  - move: {base: 500}\n    at: bar 2\n    time: 2/3b\n";
  auto out = compile_text(text);
  const ServoProgram& p = program_of(out);
  // A 4/4 bar at 120 bpm is 2000 ms; a sixth 1000/3 = 333.33 ms; six of them reach bar 2 at
  // exactly 2000 ms, so the `at: bar 2` step needs no hold.
  EXPECT_EQ(starts(p), (std::vector<std::uint32_t>{0, 333, 667, 1000, 1333, 1667, 2000}))
      << diagnostics_of(out);
  EXPECT_EQ(p.keyframes[6].time_ms, 333);  // 2/3 of a 500 ms beat
}

TEST(NoteValues, FractionsOfSecondsAndMilliseconds) {
  auto out = compile_text(R"(robot: xarm
sequence:
  - move: {base: 600}
    time: 1/3s
  - move: {base: 650}
    time: 2/3s
  - move: {base: 700}
    time: 5/2s
)");
  const ServoProgram& p = program_of(out);
  // 333.33 ms, then 666.67 ms ending at exactly 1000 ms.
  EXPECT_EQ(starts(p), (std::vector<std::uint32_t>{0, 333, 1000})) << diagnostics_of(out);
}

TEST(NoteValues, AMeterChangeKeepsTheEighth) {
  auto out = compile_text(R"(robot: xarm
tempo: 90
meter: 3/4
sequence:
  - move: {base: 600}
    time: 2bar
  - meter: 6/8
  - move: {base: 650}
    time: 1bar
  - move: {base: 700}
    at: bar 4 beat 4
    time: 1b
)");
  const ServoProgram& p = program_of(out);
  // Bars 1-2 of 3/4 at 90 bpm: 2 x 2000 ms; bar 3 (6/8, eighth at 180 bpm) starts at 4000 ms
  // and lasts 6 x 1000/3 = 2000 ms; bar 4 beat 4 is 3 eighths into bar 4: 6000 + 1000 ms.
  EXPECT_EQ(starts(p), (std::vector<std::uint32_t>{0, 4000, 6000, 7000})) << diagnostics_of(out);
  EXPECT_EQ(p.keyframes[3].time_ms, 333);  // one eighth
}

TEST(NoteValues, ATempoAfterTheMeterCountsItsBeat) {
  auto out = compile_text(R"(robot: xarm
tempo: 90
meter: 3/4
sequence:
  - move: {base: 600}
    time: 1bar
  - meter: 6/8
  - tempo: 90
  - move: {base: 650}
    time: 1bar
  - move: {base: 700}
    time: 1b
)");
  const ServoProgram& p = program_of(out);
  // After the change 90 counts eighths: 2000/3 ms each, a 6/8 bar 4000 ms.
  EXPECT_EQ(starts(p), (std::vector<std::uint32_t>{0, 2000, 6000})) << diagnostics_of(out);
  EXPECT_EQ(p.keyframes[2].time_ms, 667);
}

TEST(NoteValues, EachWayOfNamingTheTempoNote) {
  // 6/8 throughout: the beat is an eighth, and each tempo below makes it 1000/3 ms (a bar of
  // six 2000 ms): a dotted quarter (3 eighths) at 60 is 1 s; a quarter at 90 is 2000/3 ms;
  // an eighth at 180; a half (4 eighths) at 45 is 4000/3 ms.
  for (const char* tempo : {"3/8 = 60", "dotted quarter = 60", "quarter = 90", "eighth = 180",
                            "half = 45", "1/4=90", "180", "180bpm", "eighth = 180bpm"}) {
    auto out = compile_text(std::string("robot: xarm\ntempo: ") + tempo +
                            "\nmeter: 6/8\nsequence:\n  - move: {base: 600}\n    time: 1bar\n"
                            "  - move: {base: 700}\n    time: 1b\n");
    const ServoProgram& p = program_of(out);
    ASSERT_EQ(p.keyframes.size(), 2u) << tempo << "\n" << diagnostics_of(out);
    EXPECT_EQ(p.keyframes[0].time_ms, 2000) << tempo;
    EXPECT_EQ(p.keyframes[1].time_ms, 333) << tempo;
  }
  // Whole and sixteenth, and a dotted eighth, in 4/4 at a quarter of 500 ms.
  for (const char* tempo : {"whole = 30", "sixteenth = 480", "dotted eighth = 160"}) {
    auto out = compile_text(std::string("robot: xarm\ntempo: ") + tempo +
                            "\nmeter: 4/4\nsequence:\n  - move: {base: 600}\n    time: 1b\n");
    ASSERT_EQ(program_of(out).keyframes.size(), 1u) << tempo << "\n" << diagnostics_of(out);
    EXPECT_EQ(program_of(out).keyframes[0].time_ms, 500) << tempo;
  }
}

TEST(NoteValues, ATempoStepMayNameItsNote) {
  auto out = compile_text(R"(robot: xarm
tempo: 120
meter: 6/8
sequence:
  - move: {base: 600}
    time: 1b
  - tempo: dotted quarter = 60
  - move: {base: 700}
    time: 3b
)");
  const ServoProgram& p = program_of(out);
  // An eighth at 120 is 500 ms; a dotted quarter at 60 is 1000 ms, three eighths of it.
  EXPECT_EQ(starts(p), (std::vector<std::uint32_t>{0, 500})) << diagnostics_of(out);
  EXPECT_EQ(p.keyframes[1].time_ms, 1000);
}

TEST(NoteValues, TheSongsChangesKeepNotesAndNameThem) {
  auto out = compile_text(R"(robot: xarm
music:
  file: song.wav
  tempo: quarter = 90
  meter: 3/4
  changes:
    - {bar: 3, meter: 6/8}
    - {bar: 5, meter: 6/8, tempo: dotted quarter = 60}
    - {bar: 6, meter: 2/4, tempo: 3/8 = 60}
sequence:
  - move: home
    time: 1s
  - move: {base: 600}
    at: bar 3
    time: 1b
  - move: {base: 650}
    at: bar 5
    time: 1bar
  - move: {base: 700}
    at: bar 7
    time: 1b
)");
  const ServoProgram& p = program_of(out);
  // Bars 1-2: 2000 ms each; bars 3-4 in 6/8 keep the eighth (1000/3 ms): 2000 ms each, so
  // bar 5 at 8000 ms, where a dotted quarter at 60 keeps the eighth too; bar 6 at 10000 ms,
  // in 2/4 a quarter is 2/3 of a dotted quarter: 2000/3 ms, a bar 4000/3; bar 7 at 11333 ms.
  const std::vector<std::uint32_t> s = starts(p);
  ASSERT_EQ(s.size(), 7u) << diagnostics_of(out);  // home, then a hold before each cue
  EXPECT_EQ(s[2], 4000u);
  EXPECT_EQ(p.keyframes[2].time_ms, 333);
  EXPECT_EQ(s[4], 8000u);
  EXPECT_EQ(p.keyframes[4].time_ms, 2000);
  EXPECT_EQ(s[6], 11333u);
  EXPECT_EQ(p.keyframes[6].time_ms, 667);
}

TEST(NoteValues, TimeMistakesSuggestTheFraction) {
  const auto first_message = [](const std::string& time) {
    auto out = compile_text(
        "robot: xarm\ntempo: 120\nsequence:\n  - move: {base: 600}\n"
        "    time: \"" +
        time + "\"\n");
    const std::vector<std::string> m = messages(out);
    return m.empty() ? std::string() : m[0];
  };
  EXPECT_EQ(first_message("1/0b"),
            "5:11 error: '1/0b': the denominator of a fraction must be a whole number from 1 to "
            "1,000, e.g. '1/3b'");
  EXPECT_EQ(first_message("1/1001b"),
            "5:11 error: '1/1001b': the denominator of a fraction must be a whole number from 1 "
            "to 1,000, e.g. '1/3b'");
  EXPECT_EQ(first_message("12345678901234567890/3b"),
            "5:11 error: '12345678901234567890/3b': the numerator of a fraction must be a whole "
            "number up to 1,000,000; write longer times in a larger unit");
  EXPECT_EQ(first_message("1/3"),
            "5:11 error: time '1/3' has no unit; write '1/3b' (beats), '1/3bar', '1/3s' or "
            "'1/3ms'");
  EXPECT_EQ(first_message("(1/3)b"),
            "5:11 error: '(1/3)b' is not a time; a fraction is written whole over whole with the "
            "unit after it, e.g. '1/3b'");
  EXPECT_EQ(first_message("1b/3"),
            "5:11 error: '1b/3' is not a time; a fraction is written whole over whole with the "
            "unit after it, e.g. '1/3b'");
  EXPECT_EQ(first_message("2bar/3"),
            "5:11 error: '2bar/3' is not a time; a fraction is written whole over whole with the "
            "unit after it, e.g. '2/3bar'");
  EXPECT_EQ(first_message("1/3q"),
            "5:11 error: unknown time unit 'q' in '1/3q'; use ms, s, b (beats) or bar");
}

TEST(NoteValues, TempoMistakesSayWhatGoesWhere) {
  const auto first_message = [](const std::string& tempo) {
    auto out = compile_text("robot: xarm\ntempo: " + tempo +
                            "\nsequence:\n  - move: {base: 600}\n    time: 1s\n");
    const std::vector<std::string> m = messages(out);
    return m.empty() ? std::string() : m[0];
  };
  const std::string note =
      "': before '=' goes the note the tempo counts, a fraction of a whole note or its name "
      "(whole, half, quarter, eighth, sixteenth, optionally 'dotted'), e.g. 'tempo: 3/8 = 60' or "
      "'tempo: dotted quarter = 60'";
  EXPECT_EQ(first_message("crotchet = 60"), "2:8 error: 'tempo: crotchet = 60" + note);
  EXPECT_EQ(first_message("3/7 = 60"), "2:8 error: 'tempo: 3/7 = 60" + note);
  EXPECT_EQ(first_message("dotted = 60"), "2:8 error: 'tempo: dotted = 60" + note);
  EXPECT_EQ(first_message("quarter = 0"),
            "2:8 error: 'tempo: quarter = 0': after '=' goes how many of that note a minute, "
            "between 1 and 1000, e.g. 'tempo: dotted quarter = 60'");
  EXPECT_EQ(first_message("fast"),
            "2:8 error: 'tempo' must be beats per minute between 1 and 1000, e.g. 'tempo: 120'");
}

TEST(NoteValues, AnIncludedFilesTempoGivesWayToTheSong) {
  MemoryFiles files;
  files.files["main.yaml"] = R"(robot: xarm
music: {file: song.wav, tempo: 120, meter: 4/4}
sequence:
  - include: part.yaml
  - move: {base: 500}
    time: 1b
)";
  // Checked alone, the part counts its beats at 60 bpm in 6/8.
  files.files["part.yaml"] = R"(robot: xarm
tempo: 60
meter: 6/8
sequence:
  - move: {base: 600}
    time: 1bar
)";
  auto out = compile_file("main.yaml", files, CompileOptions{});
  const ServoProgram& p = program_of(out);
  // Under the song: a 4/4 bar at 120 is 2000 ms, and the main file's beat after it 500 ms.
  EXPECT_TRUE(messages(out).empty()) << diagnostics_of(out);
  EXPECT_EQ(starts(p), (std::vector<std::uint32_t>{0, 2000}));
  EXPECT_EQ(p.keyframes[0].time_ms, 2000);
  EXPECT_EQ(p.keyframes[1].time_ms, 500);

  auto alone = compile_file("part.yaml", files, CompileOptions{});
  // Alone: six eighths at 60 bpm, 6 s.
  ASSERT_EQ(program_of(alone).keyframes.size(), 1u) << diagnostics_of(alone);
  EXPECT_EQ(program_of(alone).keyframes[0].time_ms, 6000);
}

TEST(NoteValues, AnIncludedFilesOwnMeterKeepsNotesAndEndsWithIt) {
  MemoryFiles files;
  files.files["main.yaml"] = R"(robot: xarm
tempo: 90
meter: 3/4
sequence:
  - move: {base: 600}
    time: 1bar
  - include: jig.yaml
  - move: {base: 500}
    time: 1bar
)";
  files.files["jig.yaml"] = R"(robot: xarm
meter: 6/8
sequence:
  - move: {base: 700}
    time: 1bar
)";
  auto out = compile_file("main.yaml", files, CompileOptions{});
  const ServoProgram& p = program_of(out);
  // 3/4 at 90: 2000 ms; the jig's 6/8 bar keeps the eighth: 2000 ms; back in 3/4: 2000 ms.
  EXPECT_EQ(starts(p), (std::vector<std::uint32_t>{0, 2000, 4000})) << diagnostics_of(out);
  EXPECT_EQ(p.keyframes[2].time_ms, 2000);
}

}  // namespace
}  // namespace seqc::compiler
