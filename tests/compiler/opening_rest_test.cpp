// A dance may open with a rest (a first `wait`, an `at:` on the first step) and a servo's first
// move may be relative to where the robot stands: the stored group's opening actions name no
// servo, the first move starts on its written time, and a relative first move is resolved from
// a reading, from home with a note (check), or refused (compile).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "tests/compiler/lang_test_util.hpp"

namespace seqc::compiler::testing {
namespace {

using T = std::vector<lsc::ServoTarget>;
constexpr std::size_t kBase = 5;  // the xarm profile's servos in id order: base is id 6

CompileOutput compile_with(const std::string& text, RobotStart start) {
  MemoryFiles files;
  files.files["main.yaml"] = text;
  CompileOptions options;
  options.start = std::move(start);
  return compile_file("main.yaml", files, options);
}

RobotStart read_at(std::uint8_t id, std::uint16_t position) {
  RobotStart start;
  start.read[id] = position;
  return start;
}

RobotStart at_home() {
  RobotStart start;
  start.assume_home = true;
  return start;
}

TEST(OpeningRest, AWaitOfOneBeatRestsThenTheFirstMoveStartsOnBeatTwo) {
  const auto out = compile_text(R"(robot: xarm
tempo: 120
sequence:
  - wait: 1b
  - move: {base: 700}
    time: 1s
)");
  const ServoProgram& p = program_of(out);
  ASSERT_EQ(p.keyframes.size(), 2u) << diagnostics_of(out);
  // 0 - 500 ms: an action naming no servo; then the move, 500 - 1500 ms.
  EXPECT_EQ(p.keyframes[0].start_ms, 0u);
  EXPECT_EQ(p.keyframes[0].time_ms, 500);
  EXPECT_TRUE(p.keyframes[0].targets.empty());
  EXPECT_EQ(p.keyframes[1].start_ms, 500u);
  EXPECT_EQ(p.keyframes[1].time_ms, 1000);
  EXPECT_EQ(p.keyframes[1].targets, T({{6, 700}}));
  EXPECT_EQ(p.timeline.start_of(kBase, 0).value(), 500.0);
  EXPECT_TRUE(out.diagnostics.all().empty()) << diagnostics_of(out);
}

TEST(OpeningRest, AtBarOneBeatThreeStartsMovingOnBeatThree) {
  const auto out = compile_text(R"(robot: xarm
tempo: 120
meter: 4/4
sequence:
  - move: {base: 700}
    time: 1s
    at: bar 1 beat 3
)");
  const ServoProgram& p = program_of(out);
  ASSERT_EQ(p.keyframes.size(), 2u) << diagnostics_of(out);
  EXPECT_TRUE(p.keyframes[0].targets.empty());
  EXPECT_EQ(p.keyframes[0].time_ms, 1000);  // two beats at 120 bpm
  EXPECT_EQ(p.keyframes[1].start_ms, 1000u);
  EXPECT_EQ(p.timeline.start_of(kBase, 0).value(), 1000.0);
}

TEST(OpeningRest, ABeatAtNinetyBpmIsTwoThirdsOfASecondExactly) {
  const auto out = compile_text(R"(robot: xarm
tempo: 90
sequence:
  - wait: 1b
  - move: {base: 700}
    time: 1s
)");
  const ServoProgram& p = program_of(out);
  ASSERT_EQ(p.keyframes.size(), 2u) << diagnostics_of(out);
  EXPECT_DOUBLE_EQ(p.timeline.start_of(kBase, 0).value(), 2000.0 / 3.0);
  EXPECT_EQ(p.keyframes[0].time_ms, 667);  // 666.67 ms on the controller's whole milliseconds
  EXPECT_EQ(p.keyframes[1].start_ms, 667u);
}

TEST(OpeningRest, ARestLongerThanAnActionIsSeveral) {
  const auto out = compile_text(R"(robot: xarm
sequence:
  - wait: 45s
  - move: {base: 700}
    time: 1s
)");
  const ServoProgram& p = program_of(out);
  ASSERT_EQ(p.keyframes.size(), 3u) << diagnostics_of(out);
  EXPECT_TRUE(p.keyframes[0].targets.empty());
  EXPECT_TRUE(p.keyframes[1].targets.empty());
  EXPECT_EQ(p.keyframes[0].time_ms, 22500);
  EXPECT_EQ(p.keyframes[1].time_ms, 22500);
  EXPECT_EQ(p.keyframes[2].start_ms, 45000u);
}

TEST(OpeningRest, TheFirstMoveAfterTheRestIsStillCheckedFromTheFarEndOverItsOwnTime) {
  const auto out = compile_text(R"(robot: xarm
sequence:
  - wait: 1s
  - move: {base: 880}
    time: 200ms
)");
  // From 0, 880 units at 1562.5/s need 0.5632 s, said rounded up: 0.57 s.
  EXPECT_EQ(messages(out), std::vector<std::string>{
                               "4:5 warning: first move of 'base' may start anywhere in 0..1000; "
                               "from 0 it needs 0.57 s at max_speed 1562/s; this move takes "
                               "0.2 s"});
}

TEST(OpeningRest, ASequenceThatOnlyRestsIsAnError) {
  const auto out = compile_text(R"(robot: xarm
sequence:
  - wait: 1s
)");
  EXPECT_FALSE(out.program);
  EXPECT_EQ(messages(out),
            std::vector<std::string>{
                "3:3 error: the sequence only rests: it moves no servo; add a move"});
}

TEST(OpeningRest, TheCarSendsNothingUntilItsFirstDrive) {
  const auto out = compile_text(R"(robot: raspblock
sequence:
  - wait: 1s
  - drive: {x: 10}
    time: 1s
)");
  ASSERT_NE(out.raspblock_program(), nullptr) << diagnostics_of(out);
  const RaspblockProgram& p = *out.raspblock_program();
  ASSERT_EQ(p.packets.size(), 2u);
  EXPECT_EQ(p.packets[0].at_ms, 1000u);  // the drive
  EXPECT_EQ(p.packets[1].at_ms, 2000u);  // the stop
}

constexpr const char* kRelativeFirst = R"(robot: xarm
sequence:
  - move: {base: +100}
    time: 1s
)";

TEST(RelativeStart, AReadingResolvesTheFirstMoveFromWhereTheServoStands) {
  const auto out = compile_with(kRelativeFirst, read_at(6, 420));
  const ServoProgram& p = program_of(out);
  ASSERT_EQ(p.keyframes.size(), 1u);
  EXPECT_EQ(p.keyframes[0].targets, T({{6, 520}}));
  EXPECT_EQ(p.start_reads, std::vector<std::uint8_t>{6});
  // A move from a known position: it starts at the reading.
  ASSERT_EQ(p.timeline.count(kBase), 1u);
  EXPECT_EQ(p.timeline.segment(kBase, 0).from, 420.0);
  EXPECT_FALSE(p.timeline.segment(kBase, 0).from_unknown);
  EXPECT_TRUE(out.diagnostics.all().empty()) << diagnostics_of(out);
}

TEST(RelativeStart, TheLimitsAreCheckedWhereTheMoveReallyEnds) {
  const auto out = compile_with(kRelativeFirst, read_at(6, 950));
  EXPECT_FALSE(out.program);
  EXPECT_EQ(messages(out), std::vector<std::string>{
                               "3:18 error: 'base' would move to 1050 (950 +100), above its max "
                               "1000"});
}

TEST(RelativeStart, CheckAssumesHomeAndSaysSo) {
  const auto out = compile_with(kRelativeFirst, at_home());
  const ServoProgram& p = program_of(out);
  ASSERT_EQ(p.keyframes.size(), 1u);
  EXPECT_EQ(p.keyframes[0].targets, T({{6, 600}}));
  EXPECT_EQ(messages(out),
            std::vector<std::string>{
                "3:18 note: 'base' moves +100 from where the robot stands; checked here from its "
                "home 500 ('seqc upload --run' and 'seqc play' read where it stands)"});
}

TEST(RelativeStart, WithoutAReadingItIsRefusedNamingWhatReadsIt) {
  const auto out = compile_text(kRelativeFirst);
  EXPECT_FALSE(out.program);
  EXPECT_EQ(messages(out),
            std::vector<std::string>{
                "3:18 error: 'base' moves +100 from where the robot stands, which only a reading "
                "of its servos tells: 'seqc upload --run' and 'seqc play' read them first; or move "
                "'base' to an absolute position before this"});
}

TEST(RelativeStart, PwmServosCannotBeReadSoItIsAnErrorEvenInACheck) {
  const auto out = compile_with(R"(robot: lsc-16
sequence:
  - move: {ch3: +100}
    time: 1s
)",
                                at_home());
  EXPECT_FALSE(out.program);
  EXPECT_EQ(messages(out), std::vector<std::string>{
                               "3:17 error: 'ch3' has no known position yet, so the relative move "
                               "'+100' has nothing to add to; move it to an absolute position "
                               "first"});
}

TEST(RelativeStart, ALaterRelativeMoveAddsToTheReadingsMove) {
  const auto out = compile_with(R"(robot: xarm
sequence:
  - move: {base: +100}
    time: 1s
  - move: {base: -50}
    time: 1s
)",
                                read_at(6, 300));
  const ServoProgram& p = program_of(out);
  ASSERT_EQ(p.keyframes.size(), 2u);
  EXPECT_EQ(p.keyframes[0].targets, T({{6, 400}}));
  EXPECT_EQ(p.keyframes[1].targets, T({{6, 350}}));
}

}  // namespace
}  // namespace seqc::compiler::testing
