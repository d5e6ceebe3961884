// Anchors, aliases and merge keys in choreographies: the same program as the file written out,
// and mistakes inside a copy said at the anchor with a note at the alias.
#include <gtest/gtest.h>

#include "tests/compiler/lang_test_util.hpp"

namespace seqc::compiler {
namespace {

using testing::compile_text;
using testing::diagnostics_of;
using testing::messages;
using testing::program_of;

std::vector<lsc::ServoTarget> targets(std::initializer_list<std::pair<int, int>> list) {
  std::vector<lsc::ServoTarget> out;
  for (auto [id, p] : list)
    out.push_back({static_cast<std::uint8_t>(id), static_cast<std::uint16_t>(p)});
  return out;
}

// start, time and targets of every keyframe: what the controller receives.
void expect_same_motion(const ServoProgram& a, const ServoProgram& b) {
  ASSERT_EQ(a.keyframes.size(), b.keyframes.size());
  for (std::size_t i = 0; i < a.keyframes.size(); ++i) {
    EXPECT_EQ(a.keyframes[i].start_ms, b.keyframes[i].start_ms) << i;
    EXPECT_EQ(a.keyframes[i].time_ms, b.keyframes[i].time_ms) << i;
    EXPECT_EQ(a.keyframes[i].targets, b.keyframes[i].targets) << i;
  }
}

TEST(Anchors, APoseReusedByAliasIsTheWrittenOutPose) {
  auto aliased = compile_text(R"(robot: xarm
poses:
  reach: &reach {elbow: 700, shoulder: 300}
  again: *reach
sequence:
  - move: again
    time: 500ms
  - move: {claw: 200}
    time: 1s
  - move: *reach
    time: &slow 1.5s
  - move: {claw: 400}
    time: *slow
)");
  auto written = compile_text(R"(robot: xarm
poses:
  reach: {elbow: 700, shoulder: 300}
  again: {elbow: 700, shoulder: 300}
sequence:
  - move: again
    time: 500ms
  - move: {claw: 200}
    time: 1s
  - move: {elbow: 700, shoulder: 300}
    time: 1.5s
  - move: {claw: 400}
    time: 1.5s
)");
  EXPECT_EQ(diagnostics_of(aliased), "");
  const ServoProgram& p = program_of(aliased);
  expect_same_motion(p, program_of(written));
  ASSERT_EQ(p.keyframes.size(), 4u);
  EXPECT_EQ(p.keyframes[0].targets, targets({{4, 700}, {5, 300}}));
  EXPECT_EQ(p.keyframes[2].start_ms, 1500u);
  EXPECT_EQ(p.keyframes[3].time_ms, 1500);
}

TEST(Anchors, AMergeKeyWithAnOverride) {
  auto out = compile_text(R"(robot: xarm
poses:
  ready: &ready {claw: 300, elbow: 650, shoulder: 400}
  lifted:
    <<: *ready
    shoulder: 200
sequence:
  - move: lifted
    time: 1s
)");
  EXPECT_EQ(diagnostics_of(out), "");
  EXPECT_EQ(program_of(out).keyframes[0].targets, targets({{1, 300}, {4, 650}, {5, 200}}));
}

TEST(Anchors, AListOfMergesTheFirstMapWins) {
  auto out = compile_text(R"(robot: xarm
poses:
  arm: &arm {elbow: 650, shoulder: 400}
  hand: &hand {claw: 300, shoulder: 100, wrist_pitch: 500}
sequence:
  - move:
      <<: [*arm, *hand]
      claw: 250
    time: 1s
)");
  EXPECT_EQ(diagnostics_of(out), "");
  // xArm ids: claw 1, wrist_pitch 3, elbow 4, shoulder 5.
  EXPECT_EQ(program_of(out).keyframes[0].targets,
            targets({{1, 250}, {3, 500}, {4, 650}, {5, 400}}));
}

TEST(Anchors, AnUndefinedAliasIsALocatedErrorNamingTheAnchor) {
  auto out = compile_text("robot: xarm\nsequence:\n  - move: *ready\n    time: 1s\n");
  EXPECT_EQ(messages(out),
            std::vector<std::string>{
                "3:11 error: undefined alias '*ready' (no anchor '&ready' before it)"});
  EXPECT_EQ(out.program, std::nullopt);
}

TEST(Anchors, AMistakeInACopyIsSaidAtTheAnchorWithANoteAtTheAlias) {
  // '1s' is a fine time, and no position: the copy under 'elbow' is wrong, the anchor is not.
  // The unknown servo and the unknown easing are other mistakes of the same file, in the same
  // run.
  auto out = compile_text(R"(robot: xarm
sequence:
  - move: {claw: 200}
    time: &t 1s
  - move: {elbow: *t, elbw: 3}
    time: 1s
    ease: wobbly
)");
  EXPECT_EQ(messages(out),
            (std::vector<std::string>{
                "4:11 error: '1s' is not a position; write device units (500), degrees (90deg) "
                "or a relative move (+50, -10deg)",
                "5:19 note: used here",
                "5:23 error: unknown servo 'elbw' in this move; did you mean 'elbow'?",
                "7:11 error: unknown easing 'wobbly' (easings: linear, in, out, in-out; back, "
                "bounce, circ, cubic, elastic, expo, quad, quart, quint, sine, each with -in, "
                "-out or -in-out; cubic-bezier(x1, y1, x2, y2))",
            }))
      << diagnostics_of(out);
}

TEST(Anchors, AnAliasBombInAChoreographyIsOneLocatedError) {
  std::string text = "robot: xarm\nposes:\n  l0: &l0 {base: 1}\n";
  for (int i = 1; i <= 9; ++i) {
    const std::string prev = "*l" + std::to_string(i - 1);
    text += "  l" + std::to_string(i) + ": &l" + std::to_string(i) + " [" + prev;
    for (int k = 1; k < 10; ++k) text += ", " + prev;
    text += "]\n";
  }
  text += "sequence:\n  - move: l0\n    time: 1s\n";
  auto out = compile_text(text);
  // As in yaml_anchors_test.cpp, two lines lower and two columns right: the eighth alias of l5.
  EXPECT_EQ(
      messages(out),
      std::vector<std::string>{
          "8:47 error: aliases expand to more than 262144 nodes (a YAML \"billion laughs\"?)"});
}

}  // namespace
}  // namespace seqc::compiler
