// An LSC-6 sequence end to end with the real binary: `seqc emulate lsc6` on a pseudo-terminal
// and `seqc upload FILE --port PATH --run`, then the same against the in-process emu:lsc6 and
// the group commands of that dialect. The stored group is compared with actions written by
// hand from the language reference; the recorded frames with bytes written by hand from
// docs/protocol/lsc-6.md.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "tests/cli/upload_e2e_util.hpp"

namespace {

using namespace seqc::e2e;

// ch1 and ch6 move together for 500 ms, then ch3 for 300 ms; the wait holds every servo moved
// so far for 200 ms.
constexpr const char* kArm =
    "name: lsc6-e2e\n"
    "robot: lsc-6\n"
    "sequence:\n"
    "  - move: {ch1: 1000, ch6: 2000}\n"
    "    time: 500ms\n"
    "  - move: {ch3: 600}\n"
    "    time: 300ms\n"
    "  - wait: 200ms\n";

const std::vector<std::string> kExpectedGroup0 = {
    "0 0 500 1=1000 6=2000",
    "0 1 300 3=600",
    "0 2 200 1=1000 3=600 6=2000",
};

class Lsc6E2E : public ::testing::Test {
 protected:
  void SetUp() override {
    char tmpl[] = "/tmp/seqc-lsc6-e2e-XXXXXX";
    ASSERT_NE(mkdtemp(tmpl), nullptr);
    dir_ = tmpl;
    file_ = dir_ + "/arm.yaml";
    std::ofstream(file_) << kArm;
  }
  void TearDown() override {
    if (emulator_ > 0) stop_with_sigint(emulator_);
    std::string cmd = "rm -rf '" + dir_ + "'";
    (void)std::system(cmd.c_str());
  }
  void start_emulator(const std::vector<std::string>& extra = {}) {
    link_ = dir_ + "/lsc6";
    std::vector<std::string> args = {kSeqc,
                                     "emulate",
                                     "lsc6",
                                     "--link",
                                     link_,
                                     "--record",
                                     dir_ + "/record.csv",
                                     "--dump-groups",
                                     dir_ + "/groups.txt"};
    args.insert(args.end(), extra.begin(), extra.end());
    emulator_ = spawn(args, dir_ + "/emu.out", dir_ + "/emu.err");
    ASSERT_GT(emulator_, 0);
    ASSERT_TRUE(wait_for_path(link_, 200)) << slurp(dir_ + "/emu.err");
  }
  int run(const std::vector<std::string>& args, std::string* err = nullptr) {
    static int n = 0;
    const std::string o = dir_ + "/run" + std::to_string(++n) + ".out";
    const std::string e = dir_ + "/run" + std::to_string(n) + ".err";
    const int rc = wait_exit(spawn(args, o, e));
    if (err != nullptr) *err = slurp(e);
    return rc;
  }

  std::string dir_, file_, link_;
  pid_t emulator_ = -1;
};

TEST_F(Lsc6E2E, UploadsAndRunsOnTheEmulatedBoard) {
  start_emulator();
  std::string err;
  ASSERT_EQ(run({kSeqc, "upload", file_, "--port", link_, "--run"}, &err), 0) << err;
  EXPECT_NE(err.find("seqc: the controller acknowledged 3 actions into group 0"), std::string::npos)
      << err;
  EXPECT_NE(err.find("seqc: group 0 started (1 time)"), std::string::npos) << err;
  ASSERT_EQ(stop_with_sigint(emulator_), 0);
  EXPECT_EQ(stored_actions(slurp(dir_ + "/groups.txt")), kExpectedGroup0);
  const std::vector<std::string> record = lines(slurp(dir_ + "/record.csv"));
  ASSERT_EQ(record.size(), 1u + 5u) << slurp(dir_ + "/record.csv");
  EXPECT_EQ(record[1].substr(record[1].find(',')), ",ok,55 55 02 07,Stop");
  EXPECT_NE(record[2].find(",ok,55 55 0e 19 00 03 00 02 f4 01 01 e8 03 06 d0 07,"),
            std::string::npos)
      << record[2];
  EXPECT_EQ(record[5].substr(record[5].find(',')), ",ok,55 55 05 06 00 01 00,Run group=0 times=1");
}

TEST_F(Lsc6E2E, AFirmwareThatNeverAnswersRunStillStarts) {
  start_emulator({"--faults", "no-run-reply"});
  std::string err;
  ASSERT_EQ(run({kSeqc, "upload", file_, "--port", link_, "--run", "--group", "7"}, &err), 0)
      << err;
  EXPECT_NE(err.find("it did not answer Run, as some copies of the LSC-6 firmware never do: "
                     "started, unconfirmed"),
            std::string::npos)
      << err;
}

TEST_F(Lsc6E2E, InProcessBoardAndGroupCommands) {
  std::string err;
  EXPECT_EQ(run({kSeqc, "upload", file_, "--port", "emu:lsc6", "--run"}, &err), 0) << err;
  EXPECT_NE(err.find("(emu:lsc6, emulated time"), std::string::npos) << err;
  EXPECT_EQ(run({kSeqc, "group", "run", "0", "--port", "emu:lsc6"}, &err), 0) << err;
  EXPECT_EQ(run({kSeqc, "group", "stop", "--port", "emu:lsc6"}, &err), 0) << err;
  EXPECT_EQ(run({kSeqc, "group", "erase", "0", "--port", "emu:lsc6"}, &err), 2);
  EXPECT_NE(err.find("its erase command wipes every group"), std::string::npos) << err;
  EXPECT_EQ(run({kSeqc, "group", "erase", "--all", "--port", "emu:lsc6"}, &err), 0) << err;
  EXPECT_EQ(err, "seqc: every group erased\n");
  EXPECT_EQ(run({kSeqc, "battery", "--robot", "lsc-6", "--port", "/dev/null"}, &err), 2);
  EXPECT_EQ(err,
            "seqc: error: the LSC-6 board has no battery command: its firmware knows only moves, "
            "group run/stop, erasing every group and storing actions; nothing was sent\n");
}

}  // namespace
