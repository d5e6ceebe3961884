// `seqc upload` recovering, end to end with the real binaries over pseudo-terminals:
//   - the emulated controller hangs up mid-download and comes back (on a new terminal, which
//     `--link` follows, as a USB adapter re-enumerates): the upload reopens the port, says it
//     restarts, finishes, and the stored group equals `seqc compile --emit json`'s keyframes;
//   - SIGTERM (or SIGHUP) mid-download: exit 143 (129), the message says the group is empty,
//     and the emulator indeed holds no group.
// Both wait for events (a link appearing, a progress line), never for a fixed time.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/stat.h>

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "tests/cli/upload_e2e_util.hpp"

namespace {

using namespace seqc::e2e;

class UploadRecoveryE2E : public ::testing::Test {
 protected:
  void SetUp() override {
    char tmpl[] = "/tmp/seqc-recovery-e2e-XXXXXX";
    ASSERT_NE(mkdtemp(tmpl), nullptr);
    dir_ = tmpl;
    link_ = dir_ + "/xarm";
    groups_ = dir_ + "/groups.txt";
  }
  void TearDown() override {
    if (emulator_ > 0) stop_emulator();
    const std::string cmd = "rm -rf '" + dir_ + "'";
    (void)std::system(cmd.c_str());
  }
  void start_emulator(const std::vector<std::string>& extra) {
    std::vector<std::string> args = {kSeqc, "emulate",       "xarm", "--link",
                                     link_, "--dump-groups", groups_};
    args.insert(args.end(), extra.begin(), extra.end());
    emulator_ = spawn(args, dir_ + "/emu.out", dir_ + "/emu.err");
    ASSERT_GT(emulator_, 0);
    ASSERT_TRUE(wait_for_path(link_, 500)) << slurp(dir_ + "/emu.err");
  }
  int stop_emulator() { return stop_with_sigint(emulator_); }
  void stop_mid_download(int signal, int status);

  std::string dir_, link_, groups_;
  pid_t emulator_ = -1;
};

TEST_F(UploadRecoveryE2E, PortThatHangsUpAndComesBackIsReopenedAndTheUploadFinishes) {
  start_emulator({"--baud", "115200", "--faults", "hangup-at=15,back-after=300ms"});
  const std::string out = dir_ + "/up.out", err = dir_ + "/up.err";
  const int rc = wait_exit(
      spawn({kSeqc, "upload", kWalk, "--port", link_ + "@115200", "--group", "2"}, out, err));
  const std::string text = slurp(err);
  ASSERT_EQ(rc, 0) << text << slurp(dir_ + "/emu.err");
  EXPECT_NE(text.find("upload: restarting the download from step 1 (attempt 2 of 4): the "
                      "controller went away"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("the device came back on " + link_), std::string::npos) << text;
  EXPECT_NE(text.find("the port came back 1 time"), std::string::npos) << text;
  EXPECT_EQ(stop_emulator(), 0);
  // Two terminals were served: the first, and the one the device came back on.
  EXPECT_EQ(lines(slurp(dir_ + "/emu.out")).size(), 2u);

  const std::string json = dir_ + "/walk.json";
  ASSERT_EQ(wait_exit(spawn({kSeqc, "compile", kWalk, "--emit", "json"}, json, dir_ + "/c.err")),
            0);
  EXPECT_EQ(stored_actions(slurp(groups_)), compiled_actions(slurp(json), 2));
}

// A stop signal mid-download: the upload ends as Ctrl-C ends it (the group erased), and the exit
// status is the shell's for a death by that signal, 128 + its number.
void UploadRecoveryE2E::stop_mid_download(int signal, int status) {
  start_emulator({});  // 9600 baud: a long upload takes seconds
  const std::string file = dir_ + "/long.yaml";
  {
    std::ofstream f(file);
    f << "name: long\nrobot: xarm\nsequence:\n  - repeat: 150\n    do:\n"
         "      - move: {base: 300}\n        time: 100ms\n"
         "      - move: {base: 700}\n        time: 100ms\n";
  }
  const std::string out = dir_ + "/up.out", err = dir_ + "/up.err";
  const pid_t up = spawn({kSeqc, "upload", file, "--port", link_}, out, err);
  ASSERT_GT(up, 0);
  // The first progress line (a tenth of the actions acknowledged): the download is under way.
  bool started = false;
  for (int i = 0; i < 3000 && !started; ++i) {
    started = slurp(err).find("actions acknowledged") != std::string::npos;
    if (!started) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ASSERT_TRUE(started) << slurp(err);
  kill(up, signal);
  EXPECT_EQ(wait_exit(up), status);
  const std::string text = slurp(err);
  EXPECT_NE(text.find("seqc: error: interrupted"), std::string::npos) << text;
  EXPECT_NE(text.find("seqc: group 0 is now empty"), std::string::npos) << text;
  EXPECT_EQ(stop_emulator(), 0);
  EXPECT_TRUE(stored_actions(slurp(groups_)).empty());  // no valid group stored
}

TEST_F(UploadRecoveryE2E, SigtermMidDownloadExits143AndLeavesTheGroupEmpty) {
  stop_mid_download(SIGTERM, 128 + 15);
}

TEST_F(UploadRecoveryE2E, SighupMidDownloadExits129AndLeavesTheGroupEmpty) {
  stop_mid_download(SIGHUP, 128 + 1);
}

}  // namespace
