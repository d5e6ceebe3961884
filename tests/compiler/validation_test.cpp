// Mistakes: all reported in one run, with the exact wording people read.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include "tests/compiler/lang_test_util.hpp"

namespace seqc::compiler {
namespace {

using testing::compile_text;
using testing::diagnostics_of;
using testing::MemoryFiles;
using testing::messages;

std::string repeat_file(int times) {
  // The claw is already at 600 after the first pass: no speed warning, only actions.
  return "robot: xarm\nsequence:\n  - move: {claw: 600}\n    time: 1s\n  - repeat: " +
         std::to_string(times) + "\n    do:\n      - move: {claw: 600}\n        time: 20ms\n";
}

TEST(Validation, ExactlyTheBudgetFits) {
  auto out = compile_text(repeat_file(1019));
  ASSERT_TRUE(out.servo_program()) << diagnostics_of(out);
  EXPECT_EQ(out.servo_program()->keyframes.size(), 1020u);
}

TEST(Validation, OneOverTheBudgetIsReportedWithTheCount) {
  auto out = compile_text(repeat_file(1020));
  EXPECT_FALSE(out.program);
  // Action 1,021 is pass 1,020's move, after 1 s and 1,019 moves of 20 ms: at 21.38 s.
  EXPECT_EQ(messages(out), (std::vector<std::string>{
                               "7:9 error: the sequence needs at least 1021/1020 actions; a group "
                               "holds at most 1,020 (4 blocks of 255), and this step makes action "
                               "1,021 at 21.38 s",
                               "5:5 note: in pass 1020 of 1020 of this repeat",
                               "3:3 note: `seqc upload --run` stores a longer dance as "
                               "consecutive groups, each started on its bar line"}));
}

TEST(Validation, HugeNestedRepeatsAreCountedNotExpanded) {
  auto out = compile_text(R"(robot: xarm
sequence:
  - move: home
    time: 1s
  - repeat: 65535
    do:
      - repeat: 65535
        do:
          - repeat: 65535
            do:
              - wait: 20ms
)");
  ASSERT_EQ(out.diagnostics.error_count(), 1u);
  EXPECT_NE(out.diagnostics.all()[0].message.find("281462092005376/1020 actions"),
            std::string::npos)
      << out.diagnostics.all()[0].message;
}

TEST(Validation, EveryMistakeInOneRun) {
  auto out = compile_text(R"(robot: xarm
poses:
  up: {shouldr: 300}
sequence:
  - move: {claw: 1001}
    time: 1s
  - move: upp
    time: 1s
  - wait: 5
  - move: {base: 500}
    time: 15ms
)");
  EXPECT_EQ(messages(out), (std::vector<std::string>{
                               "3:8 error: unknown servo 'shouldr' in pose 'up'; did you mean "
                               "'shoulder'?",
                               "5:18 error: 'claw' would move to 1001, above its max 1000",
                               "7:11 error: unknown pose 'upp'; did you mean 'up'?",
                               "9:11 error: time '5' has no unit; write '5ms' or '5s'",
                               "11:11 error: time 15ms is below the controller's minimum of 20ms "
                               "per action",
                           }));
}

TEST(Validation, ErrorsInALoopAreReportedOnce) {
  auto out = compile_text(R"(robot: xarm
sequence:
  - move: home
    time: 1s
  - repeat: 5
    do:
      - move: {claw: 1001}
        time: 100ms
)");
  EXPECT_EQ(messages(out),
            std::vector<std::string>{"7:22 error: 'claw' would move to 1001, above its max 1000"});
}

TEST(Validation, RelativeDriftIsCaughtAtTheFirstPassThatOverflows) {
  auto out = compile_text(R"(robot: xarm
sequence:
  - move: {claw: 900}
    time: 1s
  - repeat: 5
    do:
      - move: {claw: +30}
        time: 100ms
)");
  EXPECT_EQ(messages(out), std::vector<std::string>{
                               "7:22 error: 'claw' would move to 1020 (990 +30), above its max "
                               "1000"});
}

TEST(Validation, SpeedIsAWarningUnlessStrict) {
  const std::string text = R"(robot:
  profile: lsc-16
  servos:
    arm: {id: 0, max_speed: 1000/s}
sequence:
  - move: {arm: 1000}
    time: 1.5s
  - move: {arm: 2000}
    time: 500ms
)";
  auto lenient = compile_text(text);
  ASSERT_TRUE(lenient.program);
  EXPECT_EQ(messages(lenient),
            std::vector<std::string>{"8:5 warning: 1000 in 500ms is 2000/s, above arm's 1000/s"});
  auto strict = compile_text(text, true);
  EXPECT_FALSE(strict.program);
}

TEST(Validation, EasedSpeedChecksTheFastestStep) {
  auto out = compile_text(R"(robot:
  profile: xarm
  servos:
    elbow: {max_speed: 1500/s}
sequence:
  - move: {elbow: 0}
    time: 1s
  - move: {elbow: 1000}
    time: 800ms
    ease: in-out
    steps: 4
)");
  // Linear would be 1250/s; with `steps` the controller moves in straight pieces, and
  // in-out's middle ones move 375 in 200ms.
  EXPECT_EQ(messages(out),
            std::vector<std::string>{"8:5 warning: 375 in 200ms is 1875/s, above elbow's 1500/s"});
}

TEST(Validation, FittedCurveSpeedIsItsPeak) {
  auto out = compile_text(R"(robot:
  profile: xarm
  servos:
    elbow: {max_speed: 1500/s}
sequence:
  - move: {elbow: 0}
    time: 1s
  - move: {elbow: 1000}
    time: 800ms
    ease: in-out
)");
  // Quadratic in-out peaks at twice the average speed, 2 x 1250/s, half way.
  EXPECT_EQ(messages(out),
            std::vector<std::string>{"8:5 warning: 1000 in 800ms peaks at 2500/s on this "
                                     "quad-in-out curve, above elbow's 1500/s"});
}

TEST(Validation, SpeedIsReportedInTheUnitsOfTheMove) {
  auto out = compile_text(R"(robot:
  profile: xarm
  servos:
    base: {max_speed: 300deg/s}
sequence:
  - move: {base: 0deg}
    time: 1s
  - move: {base: +110deg}
    time: 100ms
)");
  EXPECT_EQ(messages(out), std::vector<std::string>{
                               "8:5 warning: 110deg in 100ms is 1100deg/s, above base's 300deg/s"});
}

TEST(Validation, IncludeErrorsCarryTheIncludeChain) {
  MemoryFiles files;
  files.files["a.yaml"] =
      "robot: xarm\nsequence:\n  - move: home\n    time: 1s\n  - include: b.yaml\n";
  files.files["b.yaml"] = "sequence:\n  - include: c.yaml\n";
  files.files["c.yaml"] = "sequence:\n  - move: {claw: 2000}\n    time: 1s\n";
  auto out = compile_file("a.yaml", files);
  EXPECT_EQ(messages(out), (std::vector<std::string>{
                               "2:18 error: 'claw' would move to 2000, above its max 1000",
                               "2:14 note: included from here",
                               "5:14 note: included from here",
                           }));
  EXPECT_EQ(out.sources.path(out.diagnostics.all()[0].location.file), "c.yaml");
  EXPECT_EQ(out.sources.path(out.diagnostics.all()[2].location.file), "a.yaml");
}

TEST(Validation, SixteenNestedIncludesAreFine) {
  MemoryFiles files;
  files.files["main.yaml"] =
      "robot: xarm\nsequence:\n  - move: home\n    time: 1s\n  - include: d1.yaml\n";
  for (int i = 1; i <= 16; ++i) {
    files.files[fmt::format("d{}.yaml", i)] =
        "sequence:\n  - wait: 20ms\n" +
        (i < 16 ? fmt::format("  - include: d{}.yaml\n", i + 1) : std::string());
  }
  auto out = compile_file("main.yaml", files);
  ASSERT_TRUE(out.servo_program()) << diagnostics_of(out);
  EXPECT_EQ(out.servo_program()->keyframes.size(), 17u);
  files.files["d16.yaml"] += "  - include: d17.yaml\n";
  files.files["d17.yaml"] = "sequence:\n  - wait: 20ms\n";
  auto deeper = compile_file("main.yaml", files);
  ASSERT_GE(deeper.diagnostics.all().size(), 1u);
  EXPECT_EQ(deeper.diagnostics.all()[0].message,
            "includes nest more than 16 files deep; is there a runaway include chain?");
  EXPECT_EQ(deeper.diagnostics.all().size(), 1u + 16u);  // the error and 16 "included from"
}

TEST(Validation, SelfIncludeIsACycle) {
  MemoryFiles files;
  files.files["a.yaml"] =
      "robot: xarm\nsequence:\n  - move: home\n    time: 1s\n  - include: ./a.yaml\n";
  auto out = compile_file("a.yaml", files);
  EXPECT_EQ(messages(out), std::vector<std::string>{"5:14 error: include cycle: a.yaml -> a.yaml"});
}

TEST(Validation, AliasAndNameOfOneServoInOneMove) {
  auto out = compile_text(R"(robot:
  profile: xarm
  servos:
    gripper: 1
sequence:
  - move: {gripper: 600, claw: 250}
    time: 1s
)");
  EXPECT_EQ(messages(out),
            std::vector<std::string>{"6:26 error: servo 'gripper' is given twice in this move"});
}

TEST(Validation, ServoNamedLikeAnotherProfileServo) {
  auto out = compile_text(R"(robot:
  profile: xarm
  servos:
    claw: {id: 2}
sequence:
  - move: home
    time: 1s
)");
  EXPECT_EQ(messages(out), std::vector<std::string>{
                               "4:5 error: 'claw' is servo 1 on xarm; give a new name to servo 2"});
}

}  // namespace
}  // namespace seqc::compiler
