// `seqc decode` reads everything seqc writes or records, told apart by content or named with
// --from: the inputs in tests/cli/data are written by hand (see the comments in them); the
// tables are goldens in tests/cli/golden (SEQC_UPDATE_GOLDEN=1 rewrites them; review by eye).
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <fstream>

#include <cstdio>
#include <string>

#include "tests/cli/seqc_run.hpp"

namespace seqc::testing {
namespace {

struct Case {
  const char* input;
  const char* golden;
  int status;
};

class DecodeFormats : public ::testing::TestWithParam<Case> {};

TEST_P(DecodeFormats, MatchesGolden) {
  const Case& c = GetParam();
  SeqcRun r = seqc(kSource, std::string("decode tests/cli/data/") + c.input);
  EXPECT_EQ(r.status, c.status) << r.err;
  expect_golden(kCliGolden / (std::string("decode-") + c.golden + ".stdout"), r.out);
}

INSTANTIATE_TEST_SUITE_P(Inputs, DecodeFormats,
                         ::testing::Values(Case{"lsc6-upload.hex", "lsc6-upload", 0},
                                           Case{"lsc6-broken.hex", "lsc6-broken", 1},
                                           Case{"upload.trace", "trace", 0},
                                           Case{"lsc6-record.csv", "lsc6-record", 1},
                                           Case{"car.hex", "car", 0}),
                         [](const auto& test_info) {
                           std::string name = test_info.param.golden;
                           for (char& ch : name) ch = ch == '-' ? '_' : ch;
                           return name;
                         });

// stdout of `seqc compile --dry-run FILE | seqc decode -`, run by the shell as a person would.
std::string dry_run_decoded(const std::string& file, int& status) {
  const std::string cmd = "cd '" + kSource.string() + "' && '" SEQC_BIN "' compile --dry-run " +
                          file + " | '" SEQC_BIN "' decode -";
  FILE* pipe = ::popen(cmd.c_str(), "r");
  std::string out;
  if (pipe == nullptr) return out;
  char buf[4096];
  for (std::size_t n; (n = std::fread(buf, 1, sizeof buf, pipe)) > 0;) out.append(buf, n);
  const int raw = ::pclose(pipe);
  status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  return out;
}

TEST(Decode, ADryRunReadsBackThroughAPipe) {
  // Both dialects: the xArm's walk and the LSC-6 arm; every frame decodes, nothing is flagged.
  int status = -1;
  const std::string walk = dry_run_decoded("tests/data/walk-joints.yaml", status);
  EXPECT_EQ(status, 0) << walk;
  // probe, stop, barrier, steps 1-3, 29 actions, step 5, barrier
  EXPECT_NE(walk.find("# 35 frame(s), 27 action(s), 8 s total, 0 issue(s)"), std::string::npos)
      << walk;
  const std::string arm = dry_run_decoded("examples/learm.yaml", status);
  EXPECT_EQ(status, 0) << arm;
  // Stop and 42 actions
  EXPECT_NE(arm.find("# LSC-6: 37 frame(s), 36 action(s), 7.5 s total, 0 issue(s)"),
            std::string::npos)
      << arm;
}

// The questions that tell the dialects apart are named in each dialect's trace, not flagged:
// in an xArm trace the LSC-6 question (55 55 08 19: group 0, total 1, index 255, no servos,
// time 0) and an LSC-6's answer (55 55 02 19); in an LSC-6 trace the xArm question (55 55 02
// 0f) and a voltage answer (55 55 04 0f, 0x1d4c = 7500 mV).
TEST(Decode, TheDialectQuestionsAreNamedNotFlagged) {
  const fs::path dir = fs::path(SEQC_BINARY_DIR) / "tests/cli/tmp";
  fs::create_directories(dir);
  {
    std::ofstream(dir / "xarm-asks.trace")
        << "# seqc trace of emu:lsc6; t in seconds, > to the device, < from it\n"
           "# dialect: xArm / LSC-16 / LSC-32\n"
           "t=0.000000 > 55 55 02 0f\nt=0.510000 > 55 55 08 19 00 01 ff 00 00 00\n"
           "t=0.520000 < 55 55 02 19\n";
    std::ofstream(dir / "lsc6-asks.trace")
        << "# seqc trace of emu:xarm; t in seconds, > to the device, < from it\n"
           "# dialect: LSC-6\n"
           "t=0.000000 > 55 55 02 0f\nt=0.010000 < 55 55 04 0f 4c 1d\n";
  }
  SeqcRun x = seqc(dir, "decode xarm-asks.trace");
  EXPECT_EQ(x.status, 0) << x.out << x.err;
  EXPECT_NE(x.out.find("> DownloadAction group=0 total=1 index=255 time=0 servos=[] (the LSC-6 "
                       "question: no command of this dialect)"),
            std::string::npos)
      << x.out;
  EXPECT_NE(x.out.find("< ActionStored (an LSC-6 answering the LSC-6 question)"), std::string::npos)
      << x.out;
  SeqcRun l = seqc(dir, "decode lsc6-asks.trace");
  EXPECT_EQ(l.status, 0) << l.out << l.err;
  EXPECT_NE(l.out.find("> GetBatteryVoltage (the xArm question: the LSC-6 ignores it)"),
            std::string::npos)
      << l.out;
  EXPECT_NE(l.out.find("< BatteryVoltage millivolts=7500 (a board of the xArm dialect answering "
                       "the xArm question)"),
            std::string::npos)
      << l.out;
}

TEST(Decode, FromForcesAFormat) {
  // Read as the xArm dialect, CMD 25 is no request of it: every download frame is flagged.
  SeqcRun r = seqc(kSource, "decode --from hex tests/cli/data/lsc6-upload.hex");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.out.find("cannot decode 55 55 0b 19"), std::string::npos) << r.out;
  SeqcRun bad = seqc(kSource, "decode --from csv tests/cli/data/lsc6-upload.hex");
  EXPECT_EQ(bad.status, 2);
}

}  // namespace
}  // namespace seqc::testing
