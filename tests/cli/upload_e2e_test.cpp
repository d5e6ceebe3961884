// `seqc upload` end to end with the real binary: `seqc emulate xarm --link PATH --record CSV`
// runs as a separate process on a pseudo-terminal, `seqc upload tests/data/walk-joints.yaml --port
// PATH
// --run` talks to it, and the GroupDownload frames the emulator recorded must equal
// `seqc compile --emit hex` byte for byte, and the group the emulator stored (its
// --dump-groups file) must equal the keyframes of `seqc compile --emit json`, action by
// action. One more upload's stored group is compared with a group written by hand from the
// language reference. Also: a second seqc on a port the first one holds fails with "in use"
// (how fast is measured in tests/bench/upload_bench), and the in-process emulator (emu:xarm).
#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "tests/cli/upload_e2e_util.hpp"

namespace {

using namespace seqc::e2e;

class UploadE2E : public ::testing::Test {
 protected:
  void SetUp() override {
    char tmpl[] = "/tmp/seqc-upload-e2e-XXXXXX";
    ASSERT_NE(mkdtemp(tmpl), nullptr);
    dir_ = tmpl;
    link_ = dir_ + "/xarm";
    record_ = dir_ + "/record.csv";
    groups_ = dir_ + "/groups.txt";
    emulator_ = spawn(
        {kSeqc, "emulate", "xarm", "--link", link_, "--record", record_, "--dump-groups", groups_},
        dir_ + "/emu.out", dir_ + "/emu.err");
    ASSERT_GT(emulator_, 0);
    ASSERT_TRUE(wait_for_path(link_, 200)) << slurp(dir_ + "/emu.err");
  }
  void TearDown() override {
    if (emulator_ > 0) stop_emulator();
    std::string cmd = "rm -rf '" + dir_ + "'";
    (void)std::system(cmd.c_str());
  }
  int stop_emulator() { return stop_with_sigint(emulator_); }
  int run(const std::vector<std::string>& args, std::string* out = nullptr,
          std::string* err = nullptr) {
    static int n = 0;
    const std::string o = dir_ + "/run" + std::to_string(++n) + ".out";
    const std::string e = dir_ + "/run" + std::to_string(n) + ".err";
    const int rc = wait_exit(spawn(args, o, e));
    if (out != nullptr) *out = slurp(o);
    if (err != nullptr) *err = slurp(e);
    return rc;
  }

  std::string dir_, link_, record_, groups_;
  pid_t emulator_ = -1;
};

TEST_F(UploadE2E, RecordedFramesEqualTheCompiledHex) {
  std::string out, err;
  ASSERT_EQ(run({kSeqc, "upload", kWalk, "--port", link_, "--run"}, &out, &err), 0) << err;
  // The summary is on stderr; stdout carries data only (nothing, for an upload).
  EXPECT_EQ(out, "");
  EXPECT_NE(err.find("seqc: the controller acknowledged 27 actions into group 0"),
            std::string::npos)
      << err;
  EXPECT_NE(err.find("seqc: group 0 started"), std::string::npos) << err;
  EXPECT_EQ(err.find("verified"), std::string::npos);

  std::string hex, json;
  ASSERT_EQ(run({kSeqc, "compile", kWalk, "--emit", "hex"}, &hex), 0);
  ASSERT_EQ(run({kSeqc, "compile", kWalk, "--emit", "json"}, &json), 0);
  ASSERT_EQ(stop_emulator(), 0);

  // What the controller stored, as the separate emulator process wrote it on exit.
  const std::vector<std::string> stored = stored_actions(slurp(groups_));
  const std::vector<std::string> compiled = compiled_actions(json, 0);
  ASSERT_EQ(compiled.size(), 27u) << json;
  EXPECT_EQ(stored, compiled);

  // CSV: time_s,status,bytes,message. Keep the GroupDownload frames (CMD 05).
  std::vector<std::string> recorded;
  for (const auto& l : lines(slurp(record_))) {
    const auto c1 = l.find(',');
    const auto c2 = l.find(',', c1 + 1);
    const auto c3 = l.find(',', c2 + 1);
    if (c1 == std::string::npos || c3 == std::string::npos) continue;
    const std::string status = l.substr(c1 + 1, c2 - c1 - 1);
    const std::string bytes = l.substr(c2 + 1, c3 - c2 - 1);
    if (status == "ok" && bytes.size() > 11 && bytes.substr(9, 2) == "05") {
      recorded.push_back(bytes);
    }
  }
  EXPECT_EQ(recorded, lines(hex));
}

// The stored group of a small file, written by hand from docs/language.md: a move is one
// action holding only the servos it names (by id: claw 1, elbow 4, base 6), and a wait
// re-sends every servo whose position is known.
TEST_F(UploadE2E, StoredGroupMatchesAHandWrittenGroup) {
  const std::string file = dir_ + "/small.yaml";
  {
    std::ofstream f(file);
    f << "robot: xarm\n"
         "sequence:\n"
         "  - move: {claw: 200, base: 800}\n"
         "    time: 1s\n"
         "  - move: {elbow: 300}\n"
         "    time: 250ms\n"
         "  - wait: 100ms\n"
         "  - move: {base: -50}\n"
         "    time: 40ms\n";
  }
  std::string out, err;
  ASSERT_EQ(run({kSeqc, "upload", file, "--port", link_, "--group", "3"}, &out, &err), 0) << err;
  ASSERT_EQ(stop_emulator(), 0);
  const std::vector<std::string> stored = stored_actions(slurp(groups_));
  const std::vector<std::string> expected = {
      "3 0 1000 1=200 6=800",
      "3 1 250 4=300",
      "3 2 100 1=200 4=300 6=800",
      "3 3 40 6=750",
  };
  EXPECT_EQ(stored, expected) << slurp(groups_);
}

// The FLOCK locks /proc/locks lists for process `pid` (seqc locks a serial port with flock).
bool holds_a_flock(pid_t pid) {
  std::ifstream in("/proc/locks");
  for (std::string line; std::getline(in, line);) {
    std::istringstream fields(line);
    std::string n, kind, advisory, mode;
    long owner = 0;
    if (fields >> n >> kind >> advisory >> mode >> owner && kind == "FLOCK" && owner == pid) {
      return true;
    }
  }
  return false;
}

TEST_F(UploadE2E, SecondSeqcOnTheBusyPortFailsWithInUse) {
  // A group long enough (about 120 actions, several seconds at 9600 baud) that the first seqc
  // still holds the port when the second one starts, however loaded the machine is.
  const std::string file = dir_ + "/long.yaml";
  {
    std::ofstream f(file);
    f << "robot: xarm\nsequence:\n  - move: home\n    time: 1s\n  - repeat: 60\n    do:\n"
         "      - move: {base: +100}\n        time: 100ms\n"
         "      - move: {base: -100}\n        time: 100ms\n";
  }
  const pid_t first =
      spawn({kSeqc, "upload", file, "--port", link_}, dir_ + "/first.out", dir_ + "/first.err");
  ASSERT_GT(first, 0);
  // Ready when the first seqc holds the port's lock (or has already ended, which fails below).
  int status = 0;
  bool ended = false;
  while (!holds_a_flock(first)) {
    if (waitpid(first, &status, WNOHANG) == first) {
      ended = true;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  ASSERT_FALSE(ended) << "the first seqc ended before taking the port: "
                      << slurp(dir_ + "/first.err");
  std::string err;
  const int rc = run({kSeqc, "upload", kWalk, "--port", link_}, nullptr, &err);
  EXPECT_EQ(rc, 3) << err;
  EXPECT_NE(err.find("in use"), std::string::npos) << err;
  EXPECT_EQ(wait_exit(first), 0) << slurp(dir_ + "/first.err");
}

TEST(UploadCli, InvalidFileSendsNothingAndOpensNoPort) {
  const std::string bad = "/tmp/seqc-upload-bad.yaml";
  {
    std::ofstream f(bad);
    f << "robot: xarm\nsequence: [\n";
  }
  // A port that does not exist: reaching it would be exit 3, not 1.
  std::string cmd = kSeqc + " upload " + bad + " --port /dev/seqc-no-such-port >/dev/null 2>&1";
  const int status = std::system(cmd.c_str());
  EXPECT_EQ(WEXITSTATUS(status), 1);
  std::remove(bad.c_str());
}

TEST(UploadCli, EmulatorInProcessWithFaultsCompletes) {
  std::string cmd = kSeqc + " upload " + kWalk +
                    " --port 'emu:xarm?drop=0.05,corrupt=0.05,dup=0.05,seed=3' --run 2>&1";
  FILE* p = popen(cmd.c_str(), "r");
  ASSERT_NE(p, nullptr);
  char buf[512];
  std::string out;
  while (fgets(buf, sizeof buf, p) != nullptr) out += buf;
  EXPECT_EQ(WEXITSTATUS(pclose(p)), 0);
  EXPECT_NE(out.find("the controller acknowledged 27 actions into group 0"), std::string::npos)
      << out;
}

TEST(UploadCli, HangUpExitsWithDeviceFailureAndSaysTheGroupIsEmpty) {
  std::string cmd = kSeqc + " upload " + kWalk + " --port 'emu:xarm?hangup-at=20' 2>&1 >/dev/null";
  FILE* p = popen(cmd.c_str(), "r");
  ASSERT_NE(p, nullptr);
  char buf[512];
  std::string err;
  while (fgets(buf, sizeof buf, p) != nullptr) err += buf;
  EXPECT_EQ(WEXITSTATUS(pclose(p)), 4);
  EXPECT_NE(err.find("seqc: group 0 is now empty"), std::string::npos) << err;
}

// What `seqc ARGS` prints on stderr and stdout together, and its exit status.
std::string run_seqc(const std::string& args, int& status) {
  std::string cmd = kSeqc + " " + args + " 2>&1";
  FILE* p = popen(cmd.c_str(), "r");
  std::string out;
  if (p == nullptr) return out;
  char buf[512];
  while (fgets(buf, sizeof buf, p) != nullptr) out += buf;
  status = WEXITSTATUS(pclose(p));
  return out;
}

std::string upload_in_process(const std::string& port, int& status) {
  return run_seqc("upload " + kWalk + " --port '" + port + "'", status);
}

TEST(UploadCli, TheInProcessEmulatorIsPacedLikeTheLine) {
  // walk.yaml's download is 31 frames of 516 bytes and 31 six-byte acknowledgements: 702 bytes,
  // which take 0.731 s at 9600 baud (960 bytes/s); a paced upload cannot report less.
  int status = -1;
  const std::string paced = upload_in_process("emu:xarm", status);
  EXPECT_EQ(status, 0) << paced;
  const auto seconds_of = [](const std::string& text) {
    const auto at = text.find("emulated time, ");
    return at == std::string::npos ? -1.0 : std::stod(text.substr(at + 15));
  };
  EXPECT_GT(seconds_of(paced), 0.73) << paced;
  const std::string unpaced = upload_in_process("emu:xarm?baud=0", status);
  EXPECT_EQ(status, 0) << unpaced;
  EXPECT_LT(seconds_of(unpaced), 0.5) << unpaced;
}

TEST(UploadCli, RepliesSplitAcrossReadsStillPairUp) {
  int status = -1;
  const std::string out = upload_in_process("emu:xarm?split=0.5,seed=4", status);
  EXPECT_EQ(status, 0) << out;
  EXPECT_NE(out.find("the controller acknowledged 27 actions into group 0"), std::string::npos)
      << out;
}

TEST(UploadCli, ThroughTheHidFace) {
  // Discovery, HidTransport and 64-byte reports, as with a controller on USB.
  int status = -1;
  const std::string out = upload_in_process("emu:xarm-hid", status);
  EXPECT_EQ(status, 0) << out;
  EXPECT_NE(out.find("the controller acknowledged 27 actions into group 0 (hid:emu:xarm-hid "
                     "(0483:5750 LOBOT), emulated time"),
            std::string::npos)
      << out;
}

TEST(UploadCli, AFrameTooBigForAHidReportIsRefusedBeforeSending) {
  // Twenty bus servos in one action: 55 55 LEN 05 04 G b i 0b tLo tHi, then 3 x 20: 71 > 64.
  const std::string file = "/tmp/seqc-wide-" + std::to_string(getpid()) + ".yaml";
  {
    std::ofstream f(file);
    f << "robot: bus\nsequence:\n  - move: {";
    for (int i = 1; i <= 20; ++i) f << (i > 1 ? ", " : "") << "s" << i << ": 100";
    f << "}\n    time: 1s\n";
  }
  int status = -1;
  const std::string out = run_seqc("upload " + file + " --port emu:xarm-hid", status);
  EXPECT_EQ(status, 1);
  EXPECT_NE(out.find("step 4 (action 1) is a 71-byte frame, and hid:emu:xarm-hid (0483:5750 "
                     "LOBOT) carries at most 64 bytes in one report; nothing was sent"),
            std::string::npos)
      << out;
  std::remove(file.c_str());
}

TEST(UploadCli, CheckWithAHidPortSaysTheWideActionAtItsStep) {
  // Eighteen bus servos: 11 + 3 x 18 = 65 bytes, one more than a report holds; seventeen fit.
  const std::string file = "/tmp/seqc-hexapod-" + std::to_string(getpid()) + ".yaml";
  auto write = [&](int servos) {
    std::ofstream f(file);
    f << "robot: bus\nsequence:\n  - move: {";
    for (int i = 1; i <= servos; ++i) f << (i > 1 ? ", " : "") << "s" << i << ": 100";
    f << "}\n    time: 1s\n";
  };
  write(18);
  int status = -1;
  std::string out = run_seqc("check " + file + " --port emu:xarm-hid", status);
  EXPECT_EQ(status, 1);
  EXPECT_NE(out.find(file + ":3:5: error: action 1 carries 18 servos, a 65-byte frame; over USB "
                            "HID a frame holds at most 64 bytes, its 4-byte header included (at "
                            "most 17 servos per action)"),
            std::string::npos)
      << out;
  out = run_seqc("check " + file + " --port /dev/ttyUSB0", status);
  EXPECT_EQ(status, 0) << out;
  out = run_seqc("compile " + file + " --port hid", status);
  EXPECT_EQ(status, 1) << out;
  write(17);
  out = run_seqc("check " + file + " --port hid", status);
  EXPECT_EQ(status, 0) << out;
  std::remove(file.c_str());
}

}  // namespace
