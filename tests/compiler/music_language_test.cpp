// The language for music and parallel limbs: meter and bars, sections, `at`, tempo steps,
// `together` tracks, `through` curves and tolerances. Expected actions are worked out by hand
// from docs/language.md.
#include <gtest/gtest.h>

#include "tests/compiler/lang_test_util.hpp"

namespace seqc::compiler {
namespace {

using testing::compile_text;
using testing::diagnostics_of;
using testing::messages;
using testing::program_of;
using T = std::vector<lsc::ServoTarget>;

TEST(Music, BarsFollowTheMeterAndAtStartsOnABar) {
  auto out = compile_text(R"(robot: xarm
tempo: 120
meter: 3/4
sequence:
  - move: home
    time: 1bar
  - move: {base: 700}
    at: 2bar
    time: 1bar
)");
  const ServoProgram& p = program_of(out);
  // A beat is 500 ms, a bar 1500 ms. The gap from 1500 to 3000 ms is a hold of every servo.
  ASSERT_EQ(p.keyframes.size(), 3u);
  EXPECT_EQ(p.keyframes[0].time_ms, 1500);
  EXPECT_EQ(p.keyframes[1].start_ms, 1500u);
  EXPECT_EQ(p.keyframes[1].time_ms, 1500);
  EXPECT_EQ(p.keyframes[1].targets.size(), 6u);
  EXPECT_EQ(p.keyframes[2].start_ms, 3000u);
  EXPECT_EQ(p.keyframes[2].targets, T({{6, 700}}));
}

TEST(Music, AtInThePastSaysByHowMuch) {
  auto out = compile_text(R"(robot: xarm
tempo: 120
sequence:
  - move: home
    time: 3b
  - move: {base: 700}
    at: 2b
    time: 1b
)");
  EXPECT_EQ(messages(out),
            std::vector<std::string>{"7:9 error: 'at: 2b' is 500ms in the past: the steps before "
                                     "it already run until 1.5 s of this list"});
}

TEST(Music, SectionsRunWhereTheyAreNamedAndAtCountsFromTheirStart) {
  auto out = compile_text(R"(robot: xarm
tempo: 60
sections:
  nod:
    - move: {wrist_pitch: +100}
      time: 1b
    - move: {wrist_pitch: -100}
      at: 2b
      time: 1b
sequence:
  - move: home
    time: 1s
  - section: nod
  - section: nod
)");
  const ServoProgram& p = program_of(out);
  // home; per nod: up (1 s), hold (1 s), down (1 s).
  ASSERT_EQ(p.keyframes.size(), 7u);
  EXPECT_EQ(p.keyframes[1].targets, T({{3, 600}}));
  EXPECT_EQ(p.keyframes[3].start_ms, 3000u);
  EXPECT_EQ(p.keyframes[3].targets, T({{3, 500}}));
  EXPECT_EQ(p.keyframes[6].start_ms, 6000u);
  EXPECT_EQ(p.duration_ms(), 7000u);
}

TEST(Music, UnknownAndSelfPerformingSections) {
  auto out = compile_text(R"(robot: xarm
sections:
  loop:
    - section: loop
sequence:
  - move: home
    time: 1s
  - section: lop
  - section: loop
)");
  EXPECT_EQ(messages(out),
            (std::vector<std::string>{"8:14 error: unknown section 'lop'; did you mean 'loop'?",
                                      "4:16 error: section 'loop' performs itself"}));
}

TEST(Music, TempoStepChangesTheBeatFromThere) {
  auto out = compile_text(R"(robot: xarm
tempo: 120
sequence:
  - move: home
    time: 1b
  - tempo: 60
  - move: {base: 600}
    time: 1b
)");
  const ServoProgram& p = program_of(out);
  ASSERT_EQ(p.keyframes.size(), 2u);
  EXPECT_EQ(p.keyframes[0].time_ms, 500);
  EXPECT_EQ(p.keyframes[1].time_ms, 1000);
}

TEST(Music, TogetherRunsTracksSideBySide) {
  auto out = compile_text(R"(robot: xarm
sequence:
  - move: home
    time: 1s
  - together:
      swing:
        - move: {base: 800}
          time: 2s
      grip:
        - move: {claw: 650}
          time: 500ms
        - wait: 500ms
        - move: {claw: 300}
          time: 1s
  - move: {elbow: 700}
    time: 1s
)");
  const ServoProgram& p = program_of(out);
  // Boundaries of both tracks: 1000, 1500, 2000, 3000; base moves straight throughout.
  ASSERT_EQ(p.keyframes.size(), 5u) << diagnostics_of(out);
  EXPECT_EQ(p.keyframes[1].targets, T({{1, 650}, {6, 575}}));
  EXPECT_EQ(p.keyframes[2].targets, T({{1, 650}, {6, 650}}));  // the wait re-sends the claw
  EXPECT_EQ(p.keyframes[3].targets, T({{1, 300}, {6, 800}}));
  EXPECT_EQ(p.keyframes[3].time_ms, 1000);
  EXPECT_EQ(p.keyframes[4].start_ms, 3000u);
}

TEST(Music, AServoInTwoTracksNamesBothPlaces) {
  auto out = compile_text(R"(robot: xarm
sequence:
  - move: home
    time: 1s
  - together:
      a:
        - move: {base: 800}
          time: 1s
      b:
        - move: {base: 200}
          time: 1s
)");
  EXPECT_EQ(messages(out),
            (std::vector<std::string>{
                "10:11 error: 'base' moves in two tracks, 'a' and 'b'; a servo may move in one "
                "track of a 'together' only",
                "7:11 note: 'base' moves in track 'a' here"}));
}

TEST(Music, ThroughPassesEveryWaypointAtItsTime) {
  auto out = compile_text(R"(robot: xarm
poses:
  reach: {base: 700, elbow: 600}
sequence:
  - move: home
    time: 1s
  - through:
      - pose: {base: 600, elbow: 400}
        time: 500ms
      - pose: reach
        time: 700ms
    tolerance: 1
)");
  const ServoProgram& p = program_of(out);
  const Timeline& tl = p.timeline;
  // Waypoints: base 500 -> 600 -> 700, elbow 500 -> 400 -> 600, at 1000, 1500, 2200 ms.
  EXPECT_DOUBLE_EQ(*tl.value(5, 1500), 600);
  EXPECT_DOUBLE_EQ(*tl.value(3, 1500), 400);
  EXPECT_DOUBLE_EQ(*tl.value(5, 2200), 700);
  EXPECT_DOUBLE_EQ(*tl.value(3, 2200), 600);
  // The interior slope is (p2 - p0) / (t2 - t0): base 200/1200 per ms.
  EXPECT_NEAR(tl.segment(5, 1).slope_to, 200.0 / 1200.0, 1e-7);
  EXPECT_EQ(tl.segment(5, 2).slope_to, 0);
  EXPECT_LE(p.fit_error, 1.0);
  const Keyframe& last = p.keyframes.back();
  EXPECT_EQ(last.start_ms + last.time_ms, 2200u);
}

TEST(Music, EveryErrorOfAStepIsReported) {
  auto out = compile_text(R"(robot: xarm
sequence:
  - move: home
    time: 1s
  - move: {elbw: 500, base: 5000}
    time: 5ms
    ease: wobbly
)");
  EXPECT_EQ(messages(out),
            (std::vector<std::string>{
                "5:12 error: unknown servo 'elbw' in this move; did you mean 'elbow'?",
                "7:11 error: unknown easing 'wobbly'"
                " (easings: linear, in, out, in-out; back, bounce, circ, cubic, elastic, expo, "
                "quad, quart, quint, "
                "sine, each with -in, -out or -in-out; cubic-bezier(x1, y1, x2, y2))",
                "5:29 error: 'base' would move to 5000, above its max 1000",
                "6:11 error: time 5ms is below the controller's minimum of 20ms per action"}));
}

TEST(Music, OvershootingCurvesAreCheckedAlongTheWay) {
  auto out = compile_text(R"(robot: xarm
sequence:
  - move: {base: 100}
    time: 1s
  - move: {base: 950}
    time: 1s
    ease: back-out
)");
  const auto m = messages(out);
  ASSERT_EQ(m.size(), 1u) << diagnostics_of(out);
  EXPECT_EQ(m[0].rfind("5:5 error: 'base' would overshoot to 1", 0), 0u) << m[0];
  EXPECT_NE(m[0].find("on this back-out curve, above its max 1000"), std::string::npos) << m[0];
}

TEST(Music, ToleranceInDegreesAndItsMistakes) {
  auto out = compile_text(R"(robot: xarm
tolerance: 0.5deg
sequence:
  - move: home
    time: 1s
  - move: {base: 900}
    time: 1s
    ease: sine-in-out
  - tolerance: -1
)");
  EXPECT_EQ(messages(out),
            std::vector<std::string>{"9:16 error: 'tolerance' must be a positive distance in "
                                     "device units or degrees, e.g. 'tolerance: 1' or "
                                     "'tolerance: 0.5deg'"});
}

}  // namespace
}  // namespace seqc::compiler
