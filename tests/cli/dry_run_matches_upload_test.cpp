// `--dry-run` prints every frame an upload would send. These tests hold it to that, byte for
// byte: the hex of `seqc compile --dry-run FILE` (and of `seqc upload --dry-run --run FILE`) is
// compared with everything a fault-free emulated board received from `seqc upload FILE` (and
// `seqc upload --run FILE`), for an xArm file and an LSC-6 file. Each run is in-process, on a
// manual clock, against emulators the test owns (Context::hooks).
#include <gtest/gtest.h>

#include <atomic>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "runtime/cli/app.hpp"
#include "runtime/cli/context.hpp"
#include "runtime/emulator/lsc6_emulator.hpp"
#include "runtime/emulator/xarm_emulator.hpp"
#include "runtime/io/clock.hpp"
#include "runtime/io/disk.hpp"
#include "base/bytes.hpp"
#include "tests/cli/device_test_util.hpp"

namespace seqc::cli::test {
namespace {

// One fresh board of each kind, with nothing stored and no faults: a busy or dropped frame would
// mean a re-send, which the dry run rightly does not show.
using Bench = TwoBoards<io::DiskFileReader>;

std::string example(const char* name) { return std::string(SEQC_SOURCE_DIR) + "/examples/" + name; }

// The frames of a dry run's text: the hex before each "#", one frame a line, in order.
std::vector<Bytes> frames_of(const std::string& text) {
  std::vector<Bytes> frames;
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    const std::string hex = line.substr(0, line.find('#'));
    if (hex.find_first_not_of(' ') == std::string::npos) continue;
    auto bytes = parse_hex(hex);
    EXPECT_TRUE(bytes.ok()) << line;
    if (bytes.ok()) frames.push_back(*bytes);
  }
  return frames;
}

Bytes joined(const std::vector<Bytes>& frames) {
  Bytes all;
  for (const Bytes& f : frames) all.insert(all.end(), f.begin(), f.end());
  return all;
}

// Every printed line is one frame: it starts with "55 55" and a comment follows the hex.
void expect_one_frame_a_line(const std::string& text) {
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    EXPECT_EQ(line.rfind("55 55 ", 0), 0u) << line;
    EXPECT_NE(line.find("  # "), std::string::npos) << line;
  }
}

TEST(DryRunMatchesUpload, XarmCompileDryRunIsWhatUploadSends) {
  Bench dry;
  const RunResult printed = dry.run({"compile", "--dry-run", example("../tests/data/walk-joints.yaml")});
  ASSERT_EQ(printed.code, 0) << printed.err;
  expect_one_frame_a_line(printed.out);
  const std::vector<Bytes> frames = frames_of(printed.out);
  // Probe, GroupStop, barrier, the 31 GroupDownload frames of walk's 27 actions, barrier.
  EXPECT_EQ(frames.size(), 35u);
  EXPECT_TRUE(dry.xarm.received_bytes().empty());  // the dry run opened no port

  Bench live;
  const RunResult sent = live.run({"upload", example("../tests/data/walk-joints.yaml"), "--port", "emu:xarm"});
  ASSERT_EQ(sent.code, 0) << sent.err;
  EXPECT_EQ(to_hex(live.xarm.received_bytes()), to_hex(joined(frames)));
}

TEST(DryRunMatchesUpload, XarmUploadDryRunWithRunIsWhatUploadWithRunSends) {
  Bench dry;
  const RunResult printed =
      dry.run({"upload", "--dry-run", "--run", "--group", "3", example("../tests/data/walk-joints.yaml")});
  ASSERT_EQ(printed.code, 0) << printed.err;
  expect_one_frame_a_line(printed.out);
  const std::vector<Bytes> frames = frames_of(printed.out);
  // As without --run, then the first-move read, GroupRun and a barrier.
  ASSERT_EQ(frames.size(), 38u);
  // ServoPositionRead (0x15) of walk's six servos: count 06, ids 01..06, LEN = 6 + 3 = 09.
  EXPECT_EQ(to_hex(frames[35]), "55 55 09 15 06 01 02 03 04 05 06");
  // GroupRun group 3, once: 55 55 05 06 03 01 00 (docs/protocol/servo-controller.md).
  EXPECT_EQ(to_hex(frames[36]), "55 55 05 06 03 01 00");

  Bench live;
  const RunResult sent =
      live.run({"upload", "--run", "--group", "3", example("../tests/data/walk-joints.yaml"), "--port", "emu:xarm"});
  ASSERT_EQ(sent.code, 0) << sent.err;
  EXPECT_EQ(live.xarm.playing_group(), std::optional<std::uint8_t>(3));
  EXPECT_EQ(to_hex(live.xarm.received_bytes()), to_hex(joined(frames)));
}

TEST(DryRunMatchesUpload, Lsc6CompileDryRunIsWhatUploadSends) {
  Bench dry;
  const RunResult printed = dry.run({"compile", "--dry-run", example("learm.yaml")});
  ASSERT_EQ(printed.code, 0) << printed.err;
  expect_one_frame_a_line(printed.out);
  const std::vector<Bytes> frames = frames_of(printed.out);
  // Stop, then one DownloadAction per action of learm's 36.
  EXPECT_EQ(frames.size(), 37u);
  EXPECT_TRUE(dry.lsc6.received_bytes().empty());

  Bench live;
  const RunResult sent = live.run({"upload", example("learm.yaml"), "--port", "emu:lsc6"});
  ASSERT_EQ(sent.code, 0) << sent.err;
  EXPECT_EQ(to_hex(live.lsc6.received_bytes()), to_hex(joined(frames)));
}

TEST(DryRunMatchesUpload, Lsc6UploadDryRunWithRunIsWhatUploadWithRunSends) {
  Bench dry;
  const RunResult printed =
      dry.run({"upload", "--dry-run", "--run", "--times", "2", example("learm.yaml")});
  ASSERT_EQ(printed.code, 0) << printed.err;
  expect_one_frame_a_line(printed.out);
  const std::vector<Bytes> frames = frames_of(printed.out);
  ASSERT_EQ(frames.size(), 38u);
  // The LSC-6's Run: group 0, twice (docs/protocol/lsc-6.md).
  EXPECT_EQ(to_hex(frames.back()), "55 55 05 06 00 02 00");

  Bench live;
  const RunResult sent =
      live.run({"upload", "--run", "--times", "2", example("learm.yaml"), "--port", "emu:lsc6"});
  ASSERT_EQ(sent.code, 0) << sent.err;
  EXPECT_EQ(to_hex(live.lsc6.received_bytes()), to_hex(joined(frames)));
}

}  // namespace
}  // namespace seqc::cli::test
