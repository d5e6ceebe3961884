// A dance opening with a rest stores actions that name no servo before its first move, and a
// first move relative to where the robot stands is read over the port by `upload --run` and
// `play` (ServoPositionRead) and compiled from the reading; `check` assumes home with a note,
// `compile` and plain `upload` refuse it. Expected frames are written by hand from
// docs/protocol/servo-controller.md: a GroupDownload action is `55 55 LEN 05 04 G b i 0B tLo tHi
// {id posLo posHi}...`, LEN = 9 + 3 per servo.
#include <gtest/gtest.h>

#include <optional>
#include <string>

#include "tests/cli/device_test_util.hpp"

namespace seqc::cli::test {
namespace {

constexpr const char* kRelativeFirstMove = R"(robot: xarm
sequence:
  - move: {base: +100}
    time: 1s
)";

// ServoPositionRead of servo 6 only.
constexpr const char* kReadTheBase = "55 55 04 15 01 06";

bool has_part(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

TEST(RelativeFirstMove, UploadRunReadsTheBaseAndStoresItsMoveFromThere) {
  DeviceHarness h(base_at(420));
  h.files.add("rel.yaml", kRelativeFirstMove);
  const RunResult r = h.run({"upload", "rel.yaml", "--port", "emu:xarm", "--run"});
  ASSERT_EQ(r.code, 0) << r.err;
  // The read comes before the download opens (step 1 of group 0 with one action).
  const std::string got = h.received();
  const auto read = got.find(hex(kReadTheBase));
  const auto open = got.find(hex("55 55 05 05 01 00 01"));
  ASSERT_NE(read, std::string::npos) << got;
  ASSERT_NE(open, std::string::npos) << got;
  EXPECT_LT(read, open);
  // 420 + 100 = 520 = 0x0208, in 1000 ms = 0x03e8.
  EXPECT_TRUE(has_part(got, hex("55 55 0c 05 04 00 00 00 0b e8 03 06 08 02"))) << got;
  ASSERT_TRUE(h.emu.stored_group(0).has_value());
  ASSERT_EQ(h.emu.stored_group(0)->size(), 1u);
  EXPECT_EQ(h.emu.stored_group(0)->front().time_ms, 1000);
  ASSERT_EQ(h.emu.stored_group(0)->front().servos.size(), 1u);
  EXPECT_EQ(h.emu.stored_group(0)->front().servos[0].id, 6);
  EXPECT_EQ(h.emu.stored_group(0)->front().servos[0].position, 520);
  EXPECT_EQ(h.emu.playing_group(), std::optional<std::uint8_t>(0));
}

TEST(RelativeFirstMove, PlayReadsTheBaseAndSendsItsMoveFromThere) {
  DeviceHarness h(base_at(300));
  h.files.add("rel.yaml", kRelativeFirstMove);
  const RunResult r = h.run({"play", "rel.yaml", "--port", "emu:xarm"});
  ASSERT_EQ(r.code, 0) << r.err;
  // MultiServoMove of servo 6 to 400 = 0x0190 in 1000 ms.
  EXPECT_TRUE(has_part(h.received(), hex("55 55 08 03 01 e8 03 06 90 01"))) << h.received();
}

TEST(RelativeFirstMove, ALimitPassedFromTheReadingSendsNothingElse) {
  DeviceHarness h(base_at(950));
  h.files.add("rel.yaml", kRelativeFirstMove);
  const RunResult r = h.run({"upload", "rel.yaml", "--port", "emu:xarm", "--run"});
  EXPECT_EQ(r.code, 1);
  EXPECT_TRUE(has_part(r.err,
                       "rel.yaml:3:18: error: 'base' would move to 1050 (950 +100), above "
                       "its max 1000"))
      << r.err;
  EXPECT_EQ(h.received(), hex(kReadTheBase));
  EXPECT_FALSE(h.emu.stored_group(0).has_value());
}

TEST(RelativeFirstMove, CompileAndPlainUploadRefuseItNamingTheStepAndWhatReadsIt) {
  const std::string refusal =
      "rel.yaml:3:18: error: 'base' moves +100 from where the robot stands, which only a reading "
      "of its servos tells: 'seqc upload --run' and 'seqc play' read them first; or move 'base' "
      "to an absolute position before this\n";
  DeviceHarness h(base_at(420));
  h.files.add("rel.yaml", kRelativeFirstMove);
  const RunResult compiled = h.run({"compile", "rel.yaml"});
  EXPECT_EQ(compiled.code, 1);
  EXPECT_EQ(compiled.err.rfind(refusal, 0), 0u) << compiled.err;
  const RunResult stored = h.run({"upload", "rel.yaml", "--port", "emu:xarm"});
  EXPECT_EQ(stored.code, 1);
  EXPECT_EQ(stored.err.rfind(refusal, 0), 0u) << stored.err;
  EXPECT_EQ(h.received(), "");  // nothing was read or sent
}

TEST(RelativeFirstMove, CheckTakesTheRobotToStandAtHomeAndSaysSo) {
  DeviceHarness h;
  h.files.add("rel.yaml", kRelativeFirstMove);
  const RunResult r = h.run({"check", "rel.yaml"});
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.err.rfind("rel.yaml:3:18: note: 'base' moves +100 from where the robot stands; "
                        "checked here from its home 500 ('seqc upload --run' and 'seqc play' "
                        "read where it stands)\n",
                        0),
            0u)
      << r.err;
  EXPECT_EQ(r.out, "rel.yaml: 1/1020 actions, 1.000 s, fit within 0 units\n");
}

TEST(OpeningRest, UploadStoresAnActionNamingNoServoBeforeTheFirstMove) {
  DeviceHarness h(base_at(500));
  h.files.add("rest.yaml", R"(robot: xarm
tempo: 120
sequence:
  - wait: 1b
  - move: {base: 700}
    time: 1s
)");
  const RunResult r = h.run({"upload", "rest.yaml", "--port", "emu:xarm", "--run"});
  ASSERT_EQ(r.code, 0) << r.err;
  // Action 0: 500 ms (0x01f4), no servo (LEN 9); action 1: base to 700 (0x02bc) in 1000 ms.
  EXPECT_TRUE(has_part(h.received(), hex("55 55 09 05 04 00 00 00 0b f4 01") + " " +
                                         hex("55 55 0c 05 04 00 00 01 0b e8 03 06 bc 02")))
      << h.received();
  ASSERT_TRUE(h.emu.stored_group(0).has_value());
  ASSERT_EQ(h.emu.stored_group(0)->size(), 2u);
  EXPECT_TRUE(h.emu.stored_group(0)->front().servos.empty());
  EXPECT_EQ(h.emu.playing_group(), std::optional<std::uint8_t>(0));
}

TEST(OpeningRest, LivePlaySendsNothingUntilTheFirstMove) {
  DeviceHarness h(base_at(500));
  h.files.add("rest.yaml", R"(robot: xarm
sequence:
  - wait: 1s
  - move: {base: 700}
    time: 1s
)");
  const RunResult r = h.run({"play", "rest.yaml", "--port", "emu:xarm"});
  ASSERT_EQ(r.code, 0) << r.err;
  // No MultiServoMove naming no servo (55 55 05 03 00 ...); the move itself is sent.
  EXPECT_FALSE(has_part(h.received(), hex("55 55 05 03 00"))) << h.received();
  EXPECT_TRUE(has_part(h.received(), hex("55 55 08 03 01 e8 03 06 bc 02"))) << h.received();
  EXPECT_TRUE(has_part(r.err, "playing 1 moves (2 s)")) << r.err;
}

TEST(OpeningRest, TheLsc6StoresARestAsAnActionOfNoServo) {
  TwoBoards<MemoryFiles> b;
  b.files.add("rest.yaml", R"(robot: lsc-6
sequence:
  - wait: 1s
  - move: {ch1: 1700}
    time: 1s
)");
  const RunResult r = b.run({"upload", "rest.yaml", "--port", "emu:lsc6"});
  ASSERT_EQ(r.code, 0) << r.err;
  const auto stored = b.lsc6.stored_group(0);
  ASSERT_TRUE(stored.has_value());
  ASSERT_EQ(stored->size(), 2u);
  EXPECT_EQ((*stored)[0].time_ms, 1000);
  EXPECT_TRUE((*stored)[0].servos.empty());
  ASSERT_EQ((*stored)[1].servos.size(), 1u);
  EXPECT_EQ((*stored)[1].servos[0].position, 1700);
}

}  // namespace
}  // namespace seqc::cli::test
