// A file for one storing dialect uploaded to a board of the other: the uploader tells the two
// apart from the board's answers (an LSC-6 ignores GetBatteryVoltage but answers a
// DownloadAction with 55 55 02 19; an xArm-family controller answers GetBatteryVoltage with its
// voltage and ignores command 25) and `seqc upload` says which board it found and what to use
// instead, within 5 s of emulated time, exit 2, the group untouched. In-process, on a manual
// clock, against emulators the test owns (Context::hooks). Request bytes are written by hand
// from docs/protocol/servo-controller.md and docs/protocol/lsc-6.md.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <sstream>
#include <string>
#include <vector>

#include "base/bytes.hpp"
#include "runtime/cli/app.hpp"
#include "runtime/cli/context.hpp"
#include "runtime/emulator/lsc6_emulator.hpp"
#include "runtime/emulator/xarm_emulator.hpp"
#include "runtime/io/clock.hpp"
#include "tests/cli/device_test_util.hpp"

namespace seqc::cli::test {
namespace {

using std::chrono::milliseconds;

using Bench = TwoBoards<MemoryFiles>;

constexpr const char* kXarmFile = R"(name: arm
robot: xarm
sequence:
  - move: {claw: 200}
    time: 1s
)";

constexpr const char* kLsc6File = R"(name: learm
robot: lsc-6
sequence:
  - move: {ch1: 2000}
    time: 500ms
)";

TEST(WrongBoard, XarmFileOnAnLsc6SaysItIsAnLsc6) {
  Bench b;
  b.files.add("arm.yaml", kXarmFile);
  const io::TimePoint start = b.clock.now();
  RunResult r = b.run({"upload", "arm.yaml", "--port", "emu:lsc6"});
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(
      r.err,
      "seqc: error: this is an LSC-6 board; the file is for xarm: use a file with `robot: "
      "lsc-6` (or learm) for this board, or give --port the port the xArm / LSC-16 / LSC-32 is on\n"
      "seqc: the board on emu:lsc6 ignores GetBatteryVoltage and answers a DownloadAction "
      "with 55 55 02 19: it speaks the LSC-6 dialect\n"
      "seqc: group 0 is unchanged\n");
  // Five battery questions, unanswered, then the LSC-6 question: DownloadAction (19) into group
  // 0 with total 1 and index 255 (ff), no servos (N 0), time 0: LEN = 6 data bytes + 2 = 08.
  std::string battery;
  for (int i = 0; i < 5; ++i) battery += "55 55 02 0f ";
  EXPECT_EQ(to_hex(b.lsc6.received_bytes()), hex(battery + "55 55 08 19 00 01 ff 00 00 00"));
  // Nothing the board plays changed: group 0 still has no actions.
  EXPECT_EQ(b.lsc6.stored_count(0), 0);
  // Each battery wait is (4 + 6 bytes) x 1.0417 ms at 9600 baud + 500 ms = 0.510 s, five of
  // them 2.552 s; the question is answered about 16 ms later. Well within 5 s.
  const auto took = b.clock.now() - start;
  EXPECT_GE(took, milliseconds(2550));
  EXPECT_LT(took, std::chrono::seconds(5));
}

TEST(WrongBoard, Lsc6FileOnAnXarmSaysItIsAnXarm) {
  Bench b;
  b.files.add("learm.yaml", kLsc6File);
  const io::TimePoint start = b.clock.now();
  RunResult r = b.run({"upload", "learm.yaml", "--port", "emu:xarm"});
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(r.err,
            "seqc: error: this is an xArm / LSC-16 / LSC-32 board; the file is for lsc-6: use a "
            "file with `robot: xarm` (or bus, lsc-16, lsc-32) for this board, or give --port "
            "the port the LSC-6 is on\n"
            "seqc: the board on emu:xarm does not answer a DownloadAction but answers "
            "GetBatteryVoltage with its voltage: it speaks the xArm / LSC-16 / LSC-32 dialect\n"
            "seqc: group 0 is unchanged\n");
  // Stop, the one DownloadAction (group 0, total 1, index 0, one servo, 500 ms = f4 01, ch1 to
  // 2000 = d0 07), unanswered, then one battery question, answered.
  EXPECT_EQ(to_hex(b.xarm.received_bytes()),
            hex("55 55 02 07  55 55 0b 19 00 01 00 01 f4 01 01 d0 07  55 55 02 0f"));
  EXPECT_FALSE(b.xarm.stored_group(0).has_value());
  // Index 0 (also the last) waits (13 + 4 bytes) x 1.0417 ms + 500 ms + 2 s (erase) + 1 s
  // (count) = 3.518 s; the voltage comes back about 10 ms after the question. Not 50 s.
  const auto took = b.clock.now() - start;
  EXPECT_GE(took, milliseconds(3518));
  EXPECT_LT(took, std::chrono::seconds(5));
}

// A board of the file's own dialect never sees either question.
TEST(WrongBoard, TheRightBoardIsNotAsked) {
  Bench b;
  b.files.add("learm.yaml", kLsc6File);
  RunResult r = b.run({"upload", "learm.yaml", "--port", "emu:lsc6"});
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(to_hex(b.lsc6.received_bytes()),
            hex("55 55 02 07  55 55 0b 19 00 01 00 01 f4 01 01 d0 07"));
}

// A show says the same of a performer whose port has the other board, naming the performer,
// and starts nobody.
TEST(WrongBoard, AShowPerformerOnTheOtherBoardIsNamedAndNothingStarts) {
  Bench b;
  b.files.add("duo.yaml", "show: duo\nperformers:\n  arm: {file: arm.yaml, port: emu:lsc6}\n");
  b.files.add("arm.yaml", kXarmFile);
  RunResult r = b.run({"show", "duo.yaml"});
  EXPECT_EQ(r.code, 2);  // docs/cli.md: the other dialect than the file is for is a usage error
  EXPECT_NE(
      r.err.find("seqc: error: arm: this is an LSC-6 board; the file is for xarm: use a "
                 "file with `robot: lsc-6` (or learm) for this board, or give --port the port the "
                 "xArm / LSC-16 / LSC-32 is on\n"
                 "seqc: arm: the board on emu:lsc6 ignores GetBatteryVoltage and answers "
                 "a DownloadAction with 55 55 02 19: it speaks the LSC-6 dialect\n"),
      std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("seqc: nothing was started\n"), std::string::npos) << r.err;
  EXPECT_EQ(b.lsc6.stored_count(0), 0);
}

// `seqc play` asks the same questions before its first move, so no move in the other
// dialect's units reaches the servos.
TEST(WrongBoard, XarmFilePlayedOnAnLsc6SaysItIsAnLsc6AndSendsNoMove) {
  Bench b;
  b.files.add("arm.yaml", kXarmFile);
  RunResult r = b.run({"play", "arm.yaml", "--port", "emu:lsc6"});
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(r.err,
            "seqc: error: this is an LSC-6 board; the file is for xarm: use a file with `robot: "
            "lsc-6` (or learm) for this board, or give --port the port the xArm / LSC-16 / "
            "LSC-32 is on\n"
            "seqc: no move was sent\n");
  // The first-move safety read of the claw (GetServoPositions, 15: one servo, id 1), the
  // battery question, both unanswered by the LSC-6, then the LSC-6 question into group 0's
  // slot 255; no MultiServoMove (55 55 LEN 03 ...) follows.
  EXPECT_EQ(to_hex(b.lsc6.received_bytes()),
            hex("55 55 04 15 01 01  55 55 02 0f  55 55 08 19 00 01 ff 00 00 00"));
  EXPECT_EQ(b.lsc6.stored_count(0), 0);
}

TEST(WrongBoard, Lsc6FilePlayedOnAnXarmSaysItIsAnXarmAndSendsNoMove) {
  Bench b;
  b.files.add("learm.yaml", kLsc6File);
  RunResult r = b.run({"play", "learm.yaml", "--port", "emu:xarm"});
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(r.err,
            "seqc: error: this is an xArm / LSC-16 / LSC-32 board; the file is for lsc-6: use a "
            "file with `robot: xarm` (or bus, lsc-16, lsc-32) for this board, or give --port "
            "the port the LSC-6 is on\n"
            "seqc: no move was sent\n");
  // Only the battery question, which the xArm answers: the move (ch1 to 2000 us) never left.
  EXPECT_EQ(to_hex(b.xarm.received_bytes()), hex("55 55 02 0f"));
}

// On its own board an LSC-6 file's play is asked the battery question once (ignored), then
// gets its move: 55 55 08 03, one servo, 500 ms (f4 01), ch1 (01) to 2000 (d0 07).
TEST(WrongBoard, AnLsc6FilePlaysOnItsOwnBoardAfterOneUnansweredQuestion) {
  Bench b;
  b.files.add("learm.yaml", kLsc6File);
  RunResult r = b.run({"play", "learm.yaml", "--port", "emu:lsc6"});
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(to_hex(b.lsc6.received_bytes()), hex("55 55 02 0f  55 55 08 03 01 f4 01 01 d0 07"));
}

}  // namespace
}  // namespace seqc::cli::test
