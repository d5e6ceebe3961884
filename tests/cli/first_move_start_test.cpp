// The first move is safe when a stored group is started, as it is for `seqc play`: `upload
// --run` and `show` read the servos (ServoPositionRead) after the download and before the run,
// and refuse to start a group whose first move from there is faster than the servo's
// max_speed. The group stays stored; --force starts it without reading. The dry run shows the
// read where the upload makes it.
#include <gtest/gtest.h>

#include <optional>
#include <string>

#include "tests/cli/device_test_util.hpp"

namespace seqc::cli::test {
namespace {

// base from 120 to 880 in 400 ms is 760 / 0.4 = 1900 units/s, above the xarm profile's
// max_speed 1562.5/s (375 deg/s x 1000 units / 240 deg); from 700 it is 180 / 0.4 = 450/s.
constexpr const char* kFastFirst = R"(name: fast
robot: xarm
sequence:
  - move: {base: 880}
    time: 400ms
)";

// ServoPositionRead (CMD 0x15) of servo 6 only: LEN 4 = count + one id + 2.
constexpr const char* kReadBase = "55 55 04 15 01 06";
// GroupRun (CMD 0x06) of group 0, once: group 00, times 01 00.
constexpr const char* kRunGroup0 = "55 55 05 06 00 01 00";

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

TEST(FirstMoveStart, UploadRunReadsAndRefusesATooFastFirstMoveLeavingTheGroupStored) {
  DeviceHarness h(base_at(120));
  h.files.add("fast.yaml", kFastFirst);
  const RunResult r = h.run({"upload", "fast.yaml", "--port", "emu:xarm", "--run"});
  EXPECT_EQ(r.code, 1);
  EXPECT_TRUE(ends_with(r.err,
                        "seqc: error: 'base' is at 120; reaching 880 in 0.4 s is 1900 units/s, "
                        "above its max_speed 1562/s; slow the first move or pass --force; group "
                        "0 is stored but was not started\n"))
      << r.err;
  ASSERT_TRUE(h.emu.stored_group(0).has_value());
  EXPECT_EQ(h.emu.stored_group(0)->size(), 1u);
  EXPECT_EQ(h.emu.playing_group(), std::nullopt);
  // The read is the last thing sent: no GroupRun followed it.
  EXPECT_TRUE(ends_with(h.received(), hex(kReadBase))) << h.received();
  EXPECT_EQ(h.received().find(hex(kRunGroup0)), std::string::npos);
}

TEST(FirstMoveStart, UploadRunStartsAfterTheReadWhenTheFirstMoveIsSafe) {
  DeviceHarness h(base_at(700));
  h.files.add("fast.yaml", kFastFirst);
  const RunResult r = h.run({"upload", "fast.yaml", "--port", "emu:xarm", "--run"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(h.emu.playing_group(), std::optional<std::uint8_t>(0));
  EXPECT_NE(h.received().find(hex(kReadBase) + " " + hex(kRunGroup0)), std::string::npos)
      << h.received();
}

TEST(FirstMoveStart, ForceStartsWithoutReading) {
  DeviceHarness h(base_at(120));
  h.files.add("fast.yaml", kFastFirst);
  const RunResult r = h.run({"upload", "fast.yaml", "--port", "emu:xarm", "--run", "--force"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(h.emu.playing_group(), std::optional<std::uint8_t>(0));
  EXPECT_EQ(h.received().find(hex(kReadBase)), std::string::npos);
  EXPECT_NE(h.received().find(hex(kRunGroup0)), std::string::npos);
}

// --resync stores every piece, then reads before starting the first: two bars at 120 bpm in 4/4
// (2 s each) cut every bar are groups 0 and 1, both stored and neither started.
TEST(FirstMoveStart, ResyncStoresThePiecesButStartsNoneWhenTheFirstMoveIsTooFast) {
  DeviceHarness h(base_at(120));
  h.files.add("bars.yaml", R"(robot: xarm
tempo: 120
meter: 4/4
sequence:
  - move: {base: 880}
    time: 400ms
  - wait: 3600ms
)");
  const RunResult r =
      h.run({"upload", "bars.yaml", "--port", "emu:xarm", "--run", "--resync", "1"});
  EXPECT_EQ(r.code, 1);
  EXPECT_TRUE(ends_with(r.err,
                        "seqc: error: 'base' is at 120; reaching 880 in 0.4 s is 1900 units/s, "
                        "above its max_speed 1562/s; slow the first move or pass --force; groups "
                        "0-1 are stored but were not started\n"))
      << r.err;
  EXPECT_TRUE(h.emu.stored_group(0).has_value());
  EXPECT_TRUE(h.emu.stored_group(1).has_value());
  EXPECT_EQ(h.emu.playing_group(), std::nullopt);
  EXPECT_TRUE(ends_with(h.received(), hex(kReadBase))) << h.received();
}

TEST(FirstMoveStart, TheDryRunShowsTheReadBeforeTheRun) {
  DeviceHarness h;
  h.files.add("fast.yaml", kFastFirst);
  const RunResult r = h.run({"upload", "fast.yaml", "--run", "--dry-run"});
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string read_line = "55 55 04 15 01 06                         # first moves: ";
  const auto read = r.out.find(read_line);
  const auto run = r.out.find("55 55 05 06 00 01 00 ");
  ASSERT_NE(read, std::string::npos) << r.out;
  ASSERT_NE(run, std::string::npos) << r.out;
  EXPECT_LT(read, run);
  // Without --run nothing is read.
  const RunResult stored = h.run({"upload", "fast.yaml", "--dry-run"});
  EXPECT_EQ(stored.out.find("55 55 04 15"), std::string::npos) << stored.out;
}

TEST(FirstMoveStart, AShowStartsNobodyWhenAPerformersFirstMoveIsTooFast) {
  const std::string show =
      "show: duo\nperformers:\n  arm: {file: fast.yaml, port: emu:xarm, group: 1}\n";
  {
    DeviceHarness h(base_at(120));
    h.files.add("duo.yaml", show);
    h.files.add("fast.yaml", kFastFirst);
    const RunResult r = h.run({"show", "duo.yaml"});
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("seqc: error: arm: 'base' is at 120; reaching 880 in 0.4 s is 1900 "
                         "units/s, above its max_speed 1562/s; slow the first move or pass "
                         "--force\nseqc: nothing was started\n"),
              std::string::npos)
        << r.err;
    EXPECT_TRUE(h.emu.stored_group(1).has_value());
    EXPECT_EQ(h.emu.playing_group(), std::nullopt);
  }
  {
    DeviceHarness h(base_at(120));
    h.files.add("duo.yaml", show);
    h.files.add("fast.yaml", kFastFirst);
    const RunResult r = h.run({"show", "duo.yaml", "--force"});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(h.emu.playing_group(), std::optional<std::uint8_t>(1));
  }
}

}  // namespace
}  // namespace seqc::cli::test
