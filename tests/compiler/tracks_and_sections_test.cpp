// `together` blocks inside tracks, waits at the start of a track, and sections with parameters
// (`params`, `with`, `$name`, expressions of parameters). Expected actions and messages are
// worked out by hand from docs/language.md.
#include <gtest/gtest.h>

#include "base/diagnostic_rules.hpp"
#include "base/units.hpp"
#include "tests/compiler/lang_test_util.hpp"

namespace seqc::compiler {
namespace {

using testing::compile_text;
using testing::diagnostics_of;
using testing::messages;
using testing::program_of;
using T = std::vector<lsc::ServoTarget>;

// ---- nested together -------------------------------------------------------------------------

TEST(NestedTogether, ATrackMayHoldATogether) {
  auto out = compile_text(R"(robot: xarm
sequence:
  - move: home
    time: 1s
  - together:
      arm:
        - together:
            swing:
              - move: {base: 800}
                time: 1s
            reach:
              - move: {elbow: 700}
                time: 2s
        - move: {base: 500}
          time: 1s
      claw:
        - move: {claw: 300}
          time: 500ms
)");
  const ServoProgram& p = program_of(out);
  // From 1 s: claw 500 -> 300 until 1.5 s, base 500 -> 800 until 2 s, elbow 500 -> 700 until
  // 3 s, then base back to 500 until 4 s (after the inner block's longest track).
  // Boundaries 1000, 1500, 2000, 3000, 4000.
  ASSERT_EQ(p.keyframes.size(), 5u) << diagnostics_of(out);
  // At 1.5 s: base 150 of 300 (650), elbow 50 of 200 (550), claw there.
  EXPECT_EQ(p.keyframes[1].targets, T({{1, 300}, {4, 550}, {6, 650}}));
  EXPECT_EQ(p.keyframes[2].targets, T({{4, 600}, {6, 800}}));
  EXPECT_EQ(p.keyframes[3].targets, T({{4, 700}}));
  EXPECT_EQ(p.keyframes[4].start_ms, 3000u);
  EXPECT_EQ(p.keyframes[4].targets, T({{6, 500}}));
  EXPECT_EQ(p.duration_ms(), 4000u);
}

TEST(NestedTogether, AServoInTwoTracksAtAnyDepthNamesBothPlaces) {
  auto out = compile_text(R"(robot: xarm
sequence:
  - move: home
    time: 1s
  - together:
      arm:
        - together:
            swing:
              - move: {base: 800}
                time: 1s
            reach:
              - move: {base: 700}
                time: 1s
      claw:
        - move: {base: 300}
          time: 500ms
)");
  EXPECT_EQ(messages(out),
            (std::vector<std::string>{
                "12:17 error: 'base' moves in two tracks, 'swing' and 'reach'; a servo may move "
                "in one track of a 'together' only",
                "9:17 note: 'base' moves in track 'swing' here",
                "15:11 error: 'base' moves in two tracks, 'arm' and 'claw'; a servo may move in "
                "one track of a 'together' only",
                "9:17 note: 'base' moves in track 'arm' here"}));
  // The other order: the nested move comes second, and the outer block still sees it.
  auto nested_second = compile_text(R"(robot: xarm
sequence:
  - move: home
    time: 1s
  - together:
      claw:
        - move: {base: 300}
          time: 500ms
      arm:
        - together:
            swing:
              - move: {base: 800}
                time: 1s
)");
  EXPECT_EQ(messages(nested_second),
            (std::vector<std::string>{
                "12:17 error: 'base' moves in two tracks, 'claw' and 'arm'; a servo may move in "
                "one track of a 'together' only",
                "7:11 note: 'base' moves in track 'claw' here"}));
}

TEST(NestedTogether, ATrackMayMoveAServoBeforeAndInsideItsOwnBlock) {
  auto out = compile_text(R"(robot: xarm
sequence:
  - move: home
    time: 1s
  - together:
      arm:
        - move: {base: 800}
          time: 1s
        - together:
            swing:
              - move: {base: 500}
                time: 1s
            claw:
              - move: {claw: 300}
                time: 1s
)");
  const ServoProgram& p = program_of(out);
  ASSERT_EQ(p.keyframes.size(), 3u) << diagnostics_of(out);
  EXPECT_EQ(p.keyframes[2].targets, T({{1, 300}, {6, 500}}));
}

// ---- waits in tracks -------------------------------------------------------------------------

TEST(TrackWaits, AWaitAtTheStartOfATrackHolds) {
  auto out = compile_text(R"(robot: xarm
sequence:
  - move: home
    time: 1s
  - together:
      swing:
        - move: {base: 800}
          time: 2s
      grip:
        - wait: 1s
        - move: {claw: 300}
          time: 1s
)");
  const ServoProgram& p = program_of(out);
  // The claw does not move until 2 s; base runs 1 s -> 3 s straight: 650 at 2 s.
  ASSERT_EQ(p.keyframes.size(), 3u) << diagnostics_of(out);
  EXPECT_EQ(p.keyframes[1].start_ms, 1000u);
  EXPECT_EQ(p.keyframes[1].targets, T({{6, 650}}));
  EXPECT_EQ(p.keyframes[2].start_ms, 2000u);
  EXPECT_EQ(p.keyframes[2].targets, T({{1, 300}, {6, 800}}));
}

TEST(TrackWaits, AWaitThatMakesTheBlockLongestHoldsEveryKnownServo) {
  auto out = compile_text(R"(robot: xarm
sequence:
  - move: home
    time: 1s
  - together:
      swing:
        - move: {base: 800}
          time: 1s
      later:
        - wait: 3s
)");
  const ServoProgram& p = program_of(out);
  // 1 s -> 2 s base moves; 2 s -> 4 s nothing moves: a hold of every servo.
  ASSERT_EQ(p.keyframes.size(), 3u) << diagnostics_of(out);
  EXPECT_EQ(p.keyframes[2].start_ms, 2000u);
  EXPECT_EQ(p.keyframes[2].time_ms, 2000);
  EXPECT_EQ(p.keyframes[2].targets.size(), 6u);
}

TEST(TrackWaits, ABlockWhoseTracksAllStartLaterOpensWithARest) {
  auto out = compile_text(R"(robot: xarm
sequence:
  - together:
      first:
        - wait: 1s
        - move: {base: 600}
          time: 1s
      second:
        - move: {claw: 300}
          at: 500ms
          time: 1s
)");
  // Nothing has a position before the block, and neither track moves at its start: the
  // servos stand where they are until 0.5 s (an action naming none), then each first move is
  // sent with the action that ends it (claw 300 at 1.5 s, base 600 at 2 s).
  const ServoProgram& rest = program_of(out);
  ASSERT_EQ(rest.keyframes.size(), 4u) << diagnostics_of(out);
  EXPECT_EQ(rest.keyframes[0].start_ms, 0u);
  EXPECT_EQ(rest.keyframes[0].time_ms, 500);
  EXPECT_TRUE(rest.keyframes[0].targets.empty());
  EXPECT_EQ(rest.keyframes[2].start_ms, 1000u);
  EXPECT_EQ(rest.keyframes[2].targets, T({{1, 300}}));
  EXPECT_EQ(rest.keyframes[3].start_ms, 1500u);
  EXPECT_EQ(rest.keyframes[3].targets, T({{6, 600}}));
  auto fine = compile_text(R"(robot: xarm
sequence:
  - together:
      first:
        - wait: 1s
        - move: {base: 600}
          time: 1s
      second:
        - move: {claw: 300}
          time: 500ms
)");
  const ServoProgram& p = program_of(fine);
  ASSERT_EQ(p.keyframes.size(), 3u) << diagnostics_of(fine);
  EXPECT_EQ(p.keyframes[1].start_ms, 500u);  // the claw there: it holds until the base moves
  EXPECT_EQ(p.keyframes[1].targets, T({{1, 300}}));
  EXPECT_EQ(p.keyframes[2].targets, T({{6, 600}}));
}

// ---- sections with parameters ----------------------------------------------------------------

TEST(SectionParams, ValuesReplaceDefaultsWhereverTheyStand) {
  auto out = compile_text(R"(robot: xarm
tempo: 120
poses:
  low: {elbow: 300}
sections:
  nod:
    params: {amount: 40, joint: wrist_pitch, to: home}
    steps:
      - move: {$joint: +$amount}
        time: 1b
      - move: {$joint: -$amount}
        time: 1b
      - move: $to
        time: 1b
sequence:
  - move: home
    time: 1s
  - section: nod
    with: {amount: 80, joint: wrist_roll, to: low}
  - section: nod
)");
  const ServoProgram& p = program_of(out);
  // home (1 s); wrist_roll (id 2) 500 + 80, back to 500, elbow to 300; then with the defaults
  // wrist_pitch (id 3) 500 + 40, back to 500, every servo home (elbow 300 -> 500).
  ASSERT_EQ(p.keyframes.size(), 7u) << diagnostics_of(out);
  EXPECT_EQ(p.keyframes[1].targets, T({{2, 580}}));
  EXPECT_EQ(p.keyframes[1].time_ms, 500);
  EXPECT_EQ(p.keyframes[2].targets, T({{2, 500}}));
  EXPECT_EQ(p.keyframes[3].targets, T({{4, 300}}));
  EXPECT_EQ(p.keyframes[4].targets, T({{3, 540}}));
  EXPECT_EQ(p.keyframes[5].targets, T({{3, 500}}));
  EXPECT_EQ(p.keyframes[6].targets.size(), 6u);
  EXPECT_EQ(p.keyframes[6].start_ms, 3500u);
}

TEST(SectionParams, ASectionWrittenAsAListStillWorks) {
  auto out = compile_text(R"(robot: xarm
sections:
  up:
    - move: {elbow: 700}
      time: 1s
sequence:
  - move: home
    time: 1s
  - section: up
)");
  const ServoProgram& p = program_of(out);
  ASSERT_EQ(p.keyframes.size(), 2u) << diagnostics_of(out);
  EXPECT_EQ(p.keyframes[1].targets, T({{4, 700}}));
}

TEST(SectionParams, MistakesPointAtThePerformance) {
  auto out = compile_text(R"(robot: xarm
sections:
  nod:
    params: {amount: 40}
    steps:
      - move: {wrist_pitch: +$amount}
        time: 1s
      - move: {wrist_pitch: $back}
        time: 1s
sequence:
  - move: home
    time: 1s
  - section: nod
    with: {amout: 80}
  - section: nod
    with: {amount: 600}
)");
  EXPECT_EQ(messages(out),
            (std::vector<std::string>{
                "14:12 error: section 'nod' has no parameter 'amout'; did you mean 'amount'?",
                "13:14 note: section 'nod' is performed here",
                "8:29 error: unknown parameter '$back' in section 'nod'",
                "15:14 note: section 'nod' is performed here with amount: 600"}));
  auto too_far = compile_text(R"(robot: xarm
sections:
  nod:
    params: {amount: 40}
    steps:
      - move: {wrist_pitch: +$amount}
        time: 1s
sequence:
  - move: home
    time: 1s
  - section: nod
    with: {amount: 600}
)");
  EXPECT_EQ(rule_for(out.diagnostics.all()[0]).id, "unknown-name");
  EXPECT_EQ(rule_for(out.diagnostics.all()[2]).id, "unknown-name");
  // 500 + 600 is past wrist_pitch's max of 1000: the value does not fit where it lands.
  EXPECT_EQ(messages(too_far),
            (std::vector<std::string>{
                "6:29 error: 'wrist_pitch' would move to 1100 (500 +600), above its max 1000",
                "11:14 note: section 'nod' is performed here with amount: 600"}));
}

// ---- expressions of parameters -----------------------------------------------------------------

TEST(SectionExpressions, OneParameterSwingsThereAndBack) {
  auto out = compile_text(R"(robot: xarm
sections:
  swing:
    params: {swing: 100}
    steps:
      - move: {base: +$swing}
        time: 1s
      - move: {base: -$swing}
        time: 1s
sequence:
  - move: home
    time: 1s
  - section: swing
    with: {swing: -120}
  - section: swing
)");
  const ServoProgram& p = program_of(out);
  // base (id 6) from 500: +(-120) = 380, back by -(-120) to 500; then +100 = 600 and back.
  ASSERT_EQ(p.keyframes.size(), 5u) << diagnostics_of(out);
  EXPECT_EQ(p.keyframes[1].targets, T({{6, 380}}));
  EXPECT_EQ(p.keyframes[2].targets, T({{6, 500}}));
  EXPECT_EQ(p.keyframes[3].targets, T({{6, 600}}));
  EXPECT_EQ(p.keyframes[4].targets, T({{6, 500}}));
}

TEST(SectionExpressions, ScaledAndAddedValuesLandWhereTheyAreWritten) {
  auto out = compile_text(R"(robot: xarm
tempo: 120
sections:
  reach:
    params: {x: 100, beat: 1b}
    steps:
      - move: {base: $x * 2 + 300, elbow: -$x / 2}
        time: $beat / 2
      - move: {base: ($x + 50) * 4}
        time: 2 * $beat
sequence:
  - move: home
    time: 1s
  - section: reach
    with: {x: 40}
)");
  const ServoProgram& p = program_of(out);
  // base to 40 * 2 + 300 = 380 and elbow 500 - 20 = 480 over half a beat (250 ms), then base to
  // (40 + 50) * 4 = 360 over two beats (1000 ms).
  ASSERT_EQ(p.keyframes.size(), 3u) << diagnostics_of(out);
  EXPECT_EQ(p.keyframes[1].targets, T({{4, 480}, {6, 380}}));
  EXPECT_EQ(p.keyframes[1].time_ms, 250);
  EXPECT_EQ(p.keyframes[2].targets, T({{6, 360}}));
  EXPECT_EQ(p.keyframes[2].start_ms, 1250u);
  EXPECT_EQ(p.keyframes[2].time_ms, 1000);
}

TEST(SectionExpressions, ThirdsOfABeatAddUpToTheBeat) {
  if (!parse_time("1/3b")) GTEST_SKIP() << "the time parser does not read N/Db fractions yet";
  auto out = compile_text(R"(robot: xarm
tempo: 120
sections:
  triplet:
    params: {beat: 1b}
    steps:
      - move: {base: +10}
        time: $beat / 3
      - move: {base: -10}
        time: $beat / 3
      - move: {base: +10}
        time: $beat / 3
sequence:
  - move: home
    time: 1s
  - section: triplet
  - move: {base: 500}
    time: 500ms
)");
  const ServoProgram& p = program_of(out);
  EXPECT_EQ(p.timeline.end, ExactMs(2000)) << diagnostics_of(out);  // not 1999.9995
  ASSERT_EQ(p.keyframes.size(), 5u) << diagnostics_of(out);
  EXPECT_EQ(p.keyframes[4].start_ms, 1500u);
}

TEST(SectionExpressions, MistakesSayWhereWithTheValues) {
  auto out = compile_text(R"(robot: xarm
tempo: 120
sections:
  nod:
    params: {amount: 40, beat: 1b}
    steps:
      - move: {wrist_pitch: +$amount * 2}
        time: $beat
      - move: {wrist_pitch: $amount + 10deg}
        time: $beat + 100ms
sequence:
  - move: home
    time: 1s
  - section: nod
    with: {amount: 300}
)");
  EXPECT_EQ(messages(out),
            (std::vector<std::string>{
                "9:29 error: '$amount + 10deg' cannot add 300 (device units) and 10deg: device "
                "units and degrees do not mix; write both in one unit",
                "14:14 note: section 'nod' is performed here with amount: 300, beat: 1b",
                "10:15 error: '$beat + 100ms' cannot add 1b and 100ms: a beat's length in ms "
                "depends on the tempo; write both in one unit",
                "14:14 note: section 'nod' is performed here with amount: 300, beat: 1b"}));
  auto too_far = compile_text(R"(robot: xarm
sections:
  nod:
    params: {amount: 40}
    steps:
      - move: {wrist_pitch: +$amount * 2}
        time: 1s
sequence:
  - move: home
    time: 1s
  - section: nod
    with: {amount: 300}
)");
  EXPECT_EQ(messages(too_far),
            (std::vector<std::string>{
                "6:29 error: 'wrist_pitch' would move to 1100 (500 +600), above its max 1000",
                "11:14 note: section 'nod' is performed here with amount: 300"}));
  auto zero = compile_text(R"(robot: xarm
sections:
  nod:
    params: {amount: 40, parts: 2}
    steps:
      - move: {wrist_pitch: +$amount / $parts}
        time: 1s
sequence:
  - move: home
    time: 1s
  - section: nod
    with: {parts: 0}
)");
  EXPECT_EQ(messages(zero),
            (std::vector<std::string>{
                "6:29 error: '+$amount / $parts' divides by zero",
                "11:14 note: section 'nod' is performed here with amount: 40, parts: 0"}));
}

}  // namespace
}  // namespace seqc::compiler
