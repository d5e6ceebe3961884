// What programs mean: keyframes for poses, degrees, relative moves, easing, waits, repeats,
// mirroring, tempo and includes.
#include <gtest/gtest.h>

#include "tests/compiler/lang_test_util.hpp"

namespace seqc::compiler {
namespace {

using testing::compile_text;
using testing::diagnostics_of;
using testing::MemoryFiles;
using testing::program_of;

std::vector<lsc::ServoTarget> targets(std::initializer_list<std::pair<int, int>> list) {
  std::vector<lsc::ServoTarget> out;
  for (auto [id, p] : list)
    out.push_back({static_cast<std::uint8_t>(id), static_cast<std::uint16_t>(p)});
  return out;
}

TEST(Language, PoseAndInlineMoveBecomeOneKeyframeEach) {
  auto out = compile_text(R"(robot: xarm
poses:
  reach: {elbow: 700, shoulder: 300}
sequence:
  - move: reach
    time: 500ms
  - move: {claw: 200}
    time: 1.5s
)");
  const ServoProgram& p = program_of(out);
  ASSERT_EQ(p.keyframes.size(), 2u);
  EXPECT_EQ(p.keyframes[0].time_ms, 500);
  EXPECT_EQ(p.keyframes[0].start_ms, 0u);
  EXPECT_EQ(p.keyframes[0].targets, targets({{4, 700}, {5, 300}}));
  EXPECT_EQ(p.keyframes[0].source.line, 5u);
  EXPECT_EQ(p.keyframes[1].time_ms, 1500);
  EXPECT_EQ(p.keyframes[1].start_ms, 500u);
  EXPECT_EQ(p.keyframes[1].targets, targets({{1, 200}}));
  EXPECT_EQ(p.duration_ms(), 2000u);
  EXPECT_EQ(p.robot.profile, "xarm");
  EXPECT_EQ(p.robot.find_id(6)->name, "base");
}

TEST(Language, BuiltinHomeMovesEveryNamedServo) {
  auto out = compile_text("robot: xarm\nsequence:\n  - move: home\n    time: 1s\n");
  EXPECT_EQ(program_of(out).keyframes[0].targets,
            targets({{1, 500}, {2, 500}, {3, 500}, {4, 500}, {5, 500}, {6, 500}}));
}

TEST(Language, DegreesFollowTheProfile) {
  auto xarm = compile_text(
      "robot: xarm\nsequence:\n  - move: {base: 90deg, claw: 0deg, elbow: 240deg}\n    time: "
      "1s\n");
  EXPECT_EQ(program_of(xarm).keyframes[0].targets, targets({{1, 0}, {4, 1000}, {6, 375}}));
  auto lsc = compile_text(
      "robot: lsc-32\nsequence:\n  - move: {ch31: 90deg, ch0: 0deg, ch5: 180deg}\n    time: "
      "1s\n");
  EXPECT_EQ(program_of(lsc).keyframes[0].targets, targets({{0, 500}, {5, 2500}, {31, 1500}}));
}

TEST(Language, RelativeMovesAddToTheCurrentPosition) {
  auto out = compile_text(R"(robot: xarm
sequence:
  - move: {elbow: 500}
    time: 1s
  - move: {elbow: +50}
    time: 1s
  - move: {elbow: -24deg}
    time: 1s
)");
  const ServoProgram& p = program_of(out);
  EXPECT_EQ(p.keyframes[1].targets, targets({{4, 550}}));
  EXPECT_EQ(p.keyframes[2].targets, targets({{4, 450}}));  // 24deg = 100 units on the xArm
}

TEST(Language, BeatsUseTheTempo) {
  auto out = compile_text(
      "robot: xarm\ntempo: 96\nsequence:\n  - move: home\n    time: 2b\n  - wait: 0.5b\n");
  const ServoProgram& p = program_of(out);
  EXPECT_EQ(p.keyframes[0].time_ms, 1250);
  EXPECT_EQ(p.keyframes[1].time_ms, 313);  // 312.5 rounds to nearest
}

TEST(Language, WaitHoldsEveryKnownServo) {
  auto out = compile_text(R"(robot: xarm
sequence:
  - move: {claw: 100, base: 900}
    time: 1s
  - wait: 300ms
)");
  const ServoProgram& p = program_of(out);
  ASSERT_EQ(p.keyframes.size(), 2u);
  EXPECT_EQ(p.keyframes[1].time_ms, 300);
  EXPECT_EQ(p.keyframes[1].targets, targets({{1, 100}, {6, 900}}));
}

TEST(Language, LongStepsBecomeSeveralActions) {
  auto out = compile_text(R"(robot: xarm
sequence:
  - move: {elbow: 0}
    time: 1s
  - move: {elbow: 1000}
    time: 45s
  - wait: 61s
)");
  const ServoProgram& p = program_of(out);
  ASSERT_EQ(p.keyframes.size(), 1u + 2u + 3u);
  EXPECT_EQ(p.keyframes[1].time_ms, 22500);
  EXPECT_EQ(p.keyframes[1].targets, targets({{4, 500}}));
  EXPECT_EQ(p.keyframes[2].targets, targets({{4, 1000}}));
  EXPECT_EQ(p.keyframes[3].time_ms + p.keyframes[4].time_ms + p.keyframes[5].time_ms, 61000);
  for (const Keyframe& k : p.keyframes) EXPECT_LE(k.time_ms, 30000);
}

TEST(Language, EasingExpandsIntoLinearSteps) {
  auto out = compile_text(R"(robot: xarm
sequence:
  - move: {elbow: 0}
    time: 1s
  - move: {elbow: 1000}
    time: 400ms
    ease: in-out
    steps: 4
  - move: {elbow: 0}
    time: 300ms
    ease: in
    steps: 3
)");
  const ServoProgram& p = program_of(out);
  ASSERT_EQ(p.keyframes.size(), 1u + 4u + 3u);
  // in-out (quadratic): 0.125, 0.5, 0.875, 1 of the way.
  EXPECT_EQ(p.keyframes[1].targets, targets({{4, 125}}));
  EXPECT_EQ(p.keyframes[2].targets, targets({{4, 500}}));
  EXPECT_EQ(p.keyframes[3].targets, targets({{4, 875}}));
  EXPECT_EQ(p.keyframes[4].targets, targets({{4, 1000}}));
  for (int i = 1; i <= 4; ++i) EXPECT_EQ(p.keyframes[i].time_ms, 100);
  // in: 1/9, 4/9 of the way from 1000 to 0.
  EXPECT_EQ(p.keyframes[5].targets, targets({{4, 889}}));
  EXPECT_EQ(p.keyframes[6].targets, targets({{4, 556}}));
  EXPECT_EQ(p.keyframes[7].targets, targets({{4, 0}}));
}

TEST(Language, ResolutionSetsTheDefaultStepLength) {
  auto out = compile_text(R"(robot: xarm
resolution: 250ms
sequence:
  - move: {elbow: 0}
    time: 1s
  - move: {elbow: 1000}
    time: 1s
    ease: out
)");
  EXPECT_EQ(program_of(out).keyframes.size(), 1u + 4u);
}

TEST(Language, RepeatRepeatsAndRelativeMovesAccumulate) {
  auto out = compile_text(R"(robot: xarm
sequence:
  - move: {base: 100}
    time: 1s
  - repeat: 3
    do:
      - move: {base: +100}
        time: 200ms
)");
  const ServoProgram& p = program_of(out);
  // The three passes are one straight line, 100 at 1 s to 400 at 1.6 s (+100 every 200 ms), so
  // one action runs across the passes' knots: the first move's, then that one.
  ASSERT_EQ(p.keyframes.size(), 2u);
  EXPECT_EQ(p.keyframes[1].targets, targets({{6, 400}}));
  EXPECT_EQ(p.keyframes[1].start_ms, 1000u);
  EXPECT_EQ(p.keyframes[1].time_ms, 600u);
}

TEST(Language, MirrorSwapsSidesAndReflectsAroundHome) {
  auto out = compile_text(R"(robot:
  profile: lsc-16
  servos:
    left_arm: {id: 0, home: 1400}
    right_arm: {id: 1, home: 1600}
    head: 2
  mirror:
    left_arm: right_arm
    head: head
sequence:
  - move: {left_arm: 1400, right_arm: 1600, head: 1500, ch3: 1500}
    time: 1s
  - mirror:
      - move: {left_arm: 1900, head: 1700, ch3: 1000}
        time: 1s
      - move: {right_arm: +100}
        time: 1s
)");
  const ServoProgram& p = program_of(out);
  ASSERT_EQ(p.keyframes.size(), 3u);
  // left_arm +500 from its home becomes right_arm -500 from its home; head reflects in place;
  // ch3 is not in the table and is unchanged.
  EXPECT_EQ(p.keyframes[1].targets, targets({{1, 1100}, {2, 1300}, {3, 1000}}));
  EXPECT_EQ(p.keyframes[2].targets, targets({{0, 1300}}));  // right_arm +100 -> left_arm -100
}

TEST(Language, UnmentionedServosAreNotInTheKeyframe) {
  auto out = compile_text(R"(robot: xarm
sequence:
  - move: home
    time: 1s
  - move: {claw: 700}
    time: 1s
)");
  EXPECT_EQ(program_of(out).keyframes[1].targets, targets({{1, 700}}));
}

TEST(Language, IncludeResolvesRelativeToTheIncludingFile) {
  MemoryFiles files;
  files.files["dir/main.yaml"] = R"(robot: xarm
poses:
  up: {elbow: 900}
sequence:
  - move: home
    time: 1s
  - include: parts/bit.yaml
  - move: {elbow: +10}
    time: 100ms
)";
  files.files["dir/parts/bit.yaml"] = R"(tempo: 60
poses:
  down: {elbow: 100}
sequence:
  - move: up
    time: 1b
  - move: down
    time: 1b
)";
  auto out = compile_file("dir/main.yaml", files);
  const ServoProgram& p = program_of(out);
  ASSERT_EQ(p.keyframes.size(), 4u);
  EXPECT_EQ(p.keyframes[1].targets, targets({{4, 900}}));  // the includer's pose
  EXPECT_EQ(p.keyframes[1].time_ms, 1000);                 // the included file's tempo
  EXPECT_EQ(p.keyframes[2].targets, targets({{4, 100}}));
  EXPECT_EQ(p.keyframes[3].targets, targets({{4, 110}}));  // state carries across the include
  EXPECT_EQ(out.sources.path(p.keyframes[2].source.file), "dir/parts/bit.yaml");
}

TEST(Language, PerFileServosRenameAndLimit) {
  auto out = compile_text(R"(robot:
  profile: xarm
  servos:
    gripper: {id: 1, min: 200, max: 600, home: 300}
sequence:
  - move: home
    time: 1s
  - move: {claw: 600}
    time: 1s
)");
  const ServoProgram& p = program_of(out);
  EXPECT_EQ(p.keyframes[0].targets[0], (lsc::ServoTarget{1, 300}));
  EXPECT_EQ(p.robot.find_id(1)->name, "gripper");
  EXPECT_EQ(p.robot.find_id(1)->min, 200);
  ASSERT_EQ(p.keyframes.size(), 2u);
}

TEST(Language, MissingMainFileIsAReadErrorNotADiagnostic) {
  MemoryFiles files;
  auto out = compile_file("nope.yaml", files);
  ASSERT_TRUE(out.read_error);
  EXPECT_EQ(*out.read_error, "nope.yaml: No such file or directory");
  EXPECT_FALSE(out.program);
}

}  // namespace
}  // namespace seqc::compiler
