// Musical time: the tempo map (tempo and meter changes on the sequence's exact clock), `at:`
// offsets and `at: bar N beat B` positions counted through it, meter changes on bar lines, and
// the plot's bar numbers from the same map. Every instant is worked out by hand in the test.
#include <gtest/gtest.h>

#include <regex>

#include "base/diagnostic_rules.hpp"
#include "compiler/formats/plot_svg.hpp"
#include "compiler/timeline/tempo_map.hpp"
#include "tests/compiler/lang_test_util.hpp"

namespace seqc::compiler {
namespace {

using testing::compile_text;
using testing::diagnostics_of;
using testing::messages;
using testing::program_of;
using T = std::vector<lsc::ServoTarget>;

// ---- the map itself --------------------------------------------------------------------------

TEST(TempoMap, DurationsSpanningAChangeConvertPiecewise) {
  TempoMap map(120, 4);     // 500 ms a beat
  map.set_tempo(1000, 60);  // from beat 2 on, 1000 ms a beat
  // From 500 ms: one beat to 1000 ms at 500 ms a beat, then one at 1000 ms: 2000 ms.
  EXPECT_EQ(map.after_beats(500, 2), ExactMs(2000));
  // Half a beat from 750 ms: 250 ms at the old tempo.
  EXPECT_EQ(map.after_beats(750, ExactMs::ratio(1, 2)), ExactMs(1000));
  EXPECT_EQ(map.beat_at(3000), ExactMs(4));  // 2 beats + 2000 ms / 1000 ms
  EXPECT_EQ(map.time_of_beat(3), ExactMs(2000));
}

TEST(TempoMap, BarsRunOnAcrossAMeterChange) {
  TempoMap map(120, 4);
  map.set_meter(8000, 3);  // after 16 beats = bars 1-4, so bar 5 is 3/4
  EXPECT_EQ(map.bar_at(8000), ExactMs(4));
  // Bar 9 (counted from 0: 8) starts 4 bars of 3 beats after bar 5: beat 16 + 12 = 28, 14 s.
  EXPECT_EQ(map.beat_of_bar(8), ExactMs(28));
  EXPECT_EQ(map.time_of_beat(28), ExactMs(14000));
  // Two bars from 7 s (beat 14, half-way through bar 4): half a bar (2 beats) to the change,
  // then 1.5 bars of 3 = 4.5 beats: 6.5 beats of 500 ms = 3.25 s.
  EXPECT_EQ(map.after_bars(7000, 2), ExactMs(10250));
}

TEST(TempoMap, NoTempoMeansNoBeats) {
  TempoMap map;
  EXPECT_EQ(map.after_beats(0, 1), std::nullopt);
  map.set_tempo(2000, 60);  // the beat clock starts at 2 s
  EXPECT_EQ(map.beat_at(1000), ExactMs(0));
  EXPECT_EQ(map.after_beats(2000, 1), ExactMs(3000));
  EXPECT_EQ(map.after_bars(2000, 1), std::nullopt);  // no meter
}

// ---- in the language -------------------------------------------------------------------------

TEST(MusicalTime, BarBeatPositionCountsAcrossAMeterChange) {
  auto out = compile_text(R"(robot: xarm
tempo: 120
meter: 4/4
sequence:
  - move: home
    time: 4bar
  - meter: 3/4
  - move: {base: 700}
    at: bar 9 beat 3
    time: 1b
)");
  const ServoProgram& p = program_of(out);
  // At 120 bpm a beat is 500 ms. Bars 1-4 are 16 beats = 8 s; bars 5-8 are 12 beats = 6 s, so
  // bar 9 starts at 14 s, and beat 3 is two beats later: 14 s + 2 x 0.5 s = 15 s.
  ASSERT_EQ(p.keyframes.size(), 3u) << diagnostics_of(out);
  EXPECT_EQ(p.keyframes[0].time_ms, 8000);
  EXPECT_EQ(p.keyframes[1].start_ms, 8000u);  // the hold until the cue
  EXPECT_EQ(p.keyframes[1].time_ms, 7000);
  EXPECT_EQ(p.keyframes[2].start_ms, 15000u);
  EXPECT_EQ(p.keyframes[2].targets, T({{6, 700}}));
}

// A cue is a marker for the plot wherever it falls: where the steps before it end exactly on
// it (bar 2 at 120 bpm in 4/4 is 4 x 500 ms = 2 s, where the first move ends) as well as after
// a hold (bar 3 at 4 s, while the second move ends at 3 s).
TEST(MusicalTime, EveryCueIsAMarkerWithOrWithoutAHold) {
  auto out = compile_text(R"(robot: xarm
tempo: 120
meter: 4/4
sequence:
  - move: home
    time: 2s
  - move: {base: 700}
    at: bar 2
    time: 1s
  - move: {base: 300}
    at: bar 3
    time: 1s
)");
  const ServoProgram& p = program_of(out);
  std::vector<std::pair<double, std::string>> cues;
  for (const TimelineMarker& m : p.timeline.markers) {
    if (m.label.rfind("at ", 0) == 0) cues.emplace_back(m.at.value(), m.label);
  }
  EXPECT_EQ(cues, (std::vector<std::pair<double, std::string>>{{2000.0, "at bar 2"},
                                                               {4000.0, "at bar 3"}}))
      << diagnostics_of(out);
}

// The rest before a cue is a hold: the servo stays exactly where the last move left it until the
// cue, also when the curve after the cue starts vertically (circ-out, elastic-out, expo-out), where
// an early, gentler start would fit the curve within tolerance. The elbow is servo 4 on the xArm;
// 460 is where the first move leaves it, and nothing may reach the board before each cue below.
TEST(MusicalTime, TheRestBeforeACueHoldsStillBeforeAVerticalStart) {
  for (const char* ease : {"circ-out", "elastic-out", "expo-out", "circ-in-out"}) {
    for (const char* cue : {"1333ms", "1100ms", "3s", "bar 2 beat 2"}) {
      const std::string text = std::string(R"(robot: xarm
tempo: 90
meter: 4/4
sequence:
  - move: {elbow: 460, base: 500}
    time: 1s
  - move: {elbow: 700}
    at: )") + cue + R"(
    time: 1s
    ease: )" + ease + "\n";
      auto out = compile_text(text);
      const ServoProgram& p = program_of(out);
      // bar 2 beat 2 at 90 bpm in 4/4: 5 beats of 2/3 s = 3333 ms.
      const std::uint32_t cue_ms = std::string(cue) == "1333ms"   ? 1333
                                   : std::string(cue) == "1100ms" ? 1100
                                   : std::string(cue) == "3s"     ? 3000
                                                                  : 3333;
      bool moved_at_cue = false;
      for (const Keyframe& k : p.keyframes) {
        for (const lsc::ServoTarget& t : k.targets) {
          if (t.id != 4) continue;
          if (k.start_ms + k.time_ms <= cue_ms) {
            EXPECT_EQ(t.position, 460) << ease << " at " << cue << ": action at " << k.start_ms;
          } else if (k.start_ms == cue_ms && t.position != 460) {
            moved_at_cue = true;
          }
        }
      }
      EXPECT_TRUE(moved_at_cue) << ease << " at " << cue << ": the move starts on its cue";
    }
  }
}

TEST(MusicalTime, AFractionalBeatAndAPlainBar) {
  auto out = compile_text(R"(robot: xarm
tempo: 60
meter: 3/4
sequence:
  - move: home
    time: 1s
  - move: {base: 600}
    at: bar 2
    time: 1b
  - move: {base: 700}
    at: bar 3 beat 2.5
    time: 1b
)");
  const ServoProgram& p = program_of(out);
  // A beat is 1 s, a bar 3 s: bar 2 at 3 s; bar 3 at 6 s, beat 2.5 at 6 s + 1.5 s = 7.5 s.
  ASSERT_EQ(p.keyframes.size(), 5u) << diagnostics_of(out);
  EXPECT_EQ(p.keyframes[2].start_ms, 3000u);
  EXPECT_EQ(p.keyframes[2].targets, T({{6, 600}}));
  EXPECT_EQ(p.keyframes[4].start_ms, 7500u);
}

TEST(MusicalTime, APositionAlreadyPassedSaysByHowMuch) {
  auto out = compile_text(R"(robot: xarm
tempo: 120
meter: 4/4
sequence:
  - move: home
    time: 17.5s
  - move: {base: 700}
    at: bar 9 beat 3
    time: 1b
)");
  // Bar 9 starts after 8 bars of 2 s = 16 s; beat 3 is 1 s later: 17 s, 0.5 s before 17.5 s.
  EXPECT_EQ(messages(out), std::vector<std::string>{
                               "8:9 error: bar 9 beat 3 is at 17.000 s but this list is already "
                               "at 17.500 s (0.500 s past it)"});
}

TEST(MusicalTime, APositionInARepeatHoldsOnlyForTheFirstPass) {
  auto out = compile_text(R"(robot: xarm
tempo: 120
meter: 4/4
sequence:
  - move: home
    time: 1s
  - repeat: 2
    do:
      - move: {base: 700}
        at: bar 2
        time: 1bar
)");
  // Pass 1: bar 2 is at 2 s, the move ends at 4 s; pass 2 wants 2 s again.
  EXPECT_EQ(messages(out),
            std::vector<std::string>{"10:13 error: bar 2 is at 2.000 s but this list is already at "
                                     "4.000 s (2.000 s past it)"});
}

TEST(MusicalTime, AtOffsetsCountThroughTempoChanges) {
  auto out = compile_text(R"(robot: xarm
tempo: 120
sequence:
  - move: home
    time: 4b
  - tempo: 60
  - move: {base: 600}
    at: 6b
    time: 1b
)");
  const ServoProgram& p = program_of(out);
  // Four beats at 120 (4 x 0.5 s = 2 s), then two at 60 (2 x 1 s): 4 s, not 6 x 1 s.
  ASSERT_EQ(p.keyframes.size(), 3u) << diagnostics_of(out);
  EXPECT_EQ(p.keyframes[2].start_ms, 4000u);
  EXPECT_EQ(p.keyframes[2].time_ms, 1000);
}

TEST(MusicalTime, ATempoStepHoldsForEverythingAfterIt) {
  auto out = compile_text(R"(robot: xarm
tempo: 120
sections:
  slow:
    - tempo: 60
    - move: {base: 600}
      time: 1b
sequence:
  - move: home
    time: 1b
  - section: slow
  - move: {base: 500}
    time: 1b
)");
  const ServoProgram& p = program_of(out);
  // 0.5 s at 120; then the section's beat and the one after it, both at 60: 1 s each.
  ASSERT_EQ(p.keyframes.size(), 3u) << diagnostics_of(out);
  EXPECT_EQ(p.keyframes[0].time_ms, 500);
  EXPECT_EQ(p.keyframes[1].time_ms, 1000);
  EXPECT_EQ(p.keyframes[2].time_ms, 1000);
}

TEST(MusicalTime, AnIncludedFilesOwnTempoHoldsWhileItRuns) {
  testing::MemoryFiles files;
  files.files["main.yaml"] = R"(robot: xarm
tempo: 120
sequence:
  - move: home
    time: 1b
  - include: slow.yaml
  - move: {base: 500}
    time: 1b
)";
  files.files["slow.yaml"] = R"(tempo: 60
sequence:
  - move: {base: 600}
    time: 1b
)";
  auto out = compile_file("main.yaml", files);
  const ServoProgram& p = program_of(out);
  // 0.5 s at 120; the included beat at its own 60 (1 s); after it, 120 again (0.5 s).
  ASSERT_EQ(p.keyframes.size(), 3u) << diagnostics_of(out);
  EXPECT_EQ(p.keyframes[0].time_ms, 500);
  EXPECT_EQ(p.keyframes[1].time_ms, 1000);
  EXPECT_EQ(p.keyframes[2].time_ms, 500);
}

TEST(MusicalTime, TempoOrMeterInsideATrackMustMoveOut) {
  auto out = compile_text(R"(robot: xarm
tempo: 120
meter: 4/4
sequence:
  - move: home
    time: 1s
  - together:
      arm:
        - tempo: 90
      claw:
        - meter: 3/4
)");
  EXPECT_EQ(messages(out),
            (std::vector<std::string>{
                "9:18 error: 'tempo' inside a 'together' track would change the other tracks' "
                "beats too; move it out of the 'together', before or after it",
                "8:7 note: in track 'arm' of this 'together'",
                "11:18 error: 'meter' inside a 'together' track would change the other tracks' "
                "bars too; move it out of the 'together', before or after it",
                "10:7 note: in track 'claw' of this 'together'"}));
}

TEST(MusicalTime, AMeterChangeOffABarLineSaysHowFarOff) {
  auto out = compile_text(R"(robot: xarm
tempo: 120
meter: 4/4
sequence:
  - move: home
    time: 5b
  - meter: 3/4
)");
  // Five beats of 4/4: one beat into bar 2, three before bar 3.
  EXPECT_EQ(messages(out), std::vector<std::string>{
                               "7:12 error: 'meter: 3/4' must fall on a bar line, but here it is "
                               "1 beat into bar 2 (3 beats before bar 3)"});
}

TEST(MusicalTime, PositionMistakes) {
  auto out = compile_text(R"(robot: xarm
tempo: 120
meter: 3/4
sequence:
  - move: home
    time: 1s
  - move: {base: 600}
    at: bar 4 beat 4
    time: 1b
  - move: {base: 600}
    at: bar nine
    time: 1b
)");
  EXPECT_EQ(messages(out),
            (std::vector<std::string>{
                "8:9 error: bar 4 has 3 beats: 'beat 4' is past its end",
                "11:9 error: 'at: bar nine' is not a position; write 'bar N' or 'bar N beat B' "
                "(counted from 1, e.g. 'at: bar 9 beat 3'), or a time from the start of this "
                "list such as 'at: 8bar'"}));
  auto no_meter = compile_text(R"(robot: xarm
tempo: 120
sequence:
  - move: home
    time: 1s
  - move: {base: 600}
    at: bar 4
    time: 1b
)");
  EXPECT_EQ(messages(no_meter),
            std::vector<std::string>{"7:9 error: 'at: bar 4' counts bars from the start of the "
                                     "sequence; set 'tempo' and 'meter' at the top of the file"});
}

TEST(MusicalTime, ThePlotNumbersBarsAcrossAMeterChange) {
  auto out = compile_text(R"(robot: xarm
tempo: 120
meter: 4/4
sequence:
  - move: home
    time: 4b
  - meter: 3/4
  - move: {base: 600}
    time: 6b
)");
  const ServoProgram& p = program_of(out);
  const std::string svg = compiler::plot_servo_program(p, {});
  const std::size_t from = svg.find("<g class=\"grid\">");
  ASSERT_NE(from, std::string::npos);
  const std::string grid = svg.substr(from, svg.find("</g>", from) - from);
  // Beats 0-3 are bar 1 (4/4), then 3/4: bar 2 on beat 4, bar 3 on beat 7, bar 4 on beat 10,
  // the end (5 s). Counting 4/4 throughout would label beats 0, 4 and 8 only.
  std::vector<std::string> labels;
  const std::regex text(">([0-9]+)</text>");
  for (auto it = std::sregex_iterator(grid.begin(), grid.end(), text); it != std::sregex_iterator();
       ++it) {
    labels.push_back((*it)[1]);
  }
  EXPECT_EQ(labels, (std::vector<std::string>{"1", "2", "3", "4"}));
  // Eleven beat lines, beats 0 to 10.
  std::size_t lines = 0;
  for (std::size_t at = grid.find("<line"); at != std::string::npos;
       at = grid.find("<line", at + 1)) {
    ++lines;
  }
  EXPECT_EQ(lines, 11u);
}

TEST(MusicalTime, TheNewMistakesHaveTheirRules) {
  // `seqc check --format json|sarif` names each diagnostic's rule from its wording.
  auto first_rule = [](const std::string& text) {
    const CompileOutput out = compile_text(text);
    return out.diagnostics.all().empty() ? std::string("none")
                                         : std::string(rule_for(out.diagnostics.all()[0]).id);
  };
  EXPECT_EQ(first_rule("robot: xarm\ntempo: 120\nmeter: 4/4\nsequence:\n  - move: home\n"
                       "    time: 3s\n  - move: {base: 600}\n    at: bar 2\n    time: 1b\n"),
            "timing");  // bar 2 at 2 s, the list at 3 s
  EXPECT_EQ(first_rule("robot: xarm\ntempo: 120\nmeter: 4/4\nsequence:\n  - move: home\n"
                       "    time: 1b\n  - meter: 3/4\n"),
            "timing");
  EXPECT_EQ(first_rule("robot: xarm\ntempo: 120\nmeter: 4/4\nsequence:\n  - move: home\n"
                       "    time: 1s\n  - move: {base: 600}\n    at: bar two\n    time: 1b\n"),
            "timing");
  EXPECT_EQ(first_rule("robot: xarm\nsequence:\n  - move: home\n    time: 1s\n"
                       "  - together:\n      a:\n        - tempo: 60\n"),
            "structure");
}

}  // namespace
}  // namespace seqc::compiler
