// `seqc compile|check|play` on Raspblock files, run in-process on a ManualClock (so `play`
// takes no real time), compared with goldens under tests/golden/raspblock. small.hex is
// written by hand (the arithmetic is in tests/compiler/raspblock_stream_test.cpp); the
// .stderr goldens are what a person reads and were reviewed line by line.
#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "compiler/compile.hpp"
#include "runtime/cli/app.hpp"
#include "runtime/cli/commands.hpp"
#include "runtime/io/clock.hpp"
#include "runtime/io/disk.hpp"

namespace seqc::cli {
namespace {

namespace fs = std::filesystem;
const fs::path kSource = SEQC_SOURCE_DIR;
const fs::path kGolden = kSource / "tests/golden/raspblock";

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

struct SeqcRun {
  int status = -1;
  std::string out;
  std::string err;
  io::TimePoint clock_end{0};
};

// Runs seqc in-process from the source root (paths in messages stay relative).
SeqcRun seqc(std::vector<std::string> args, bool interrupted = false) {
  const fs::path before = fs::current_path();
  fs::current_path(kSource);
  std::ostringstream out, err;
  io::ManualClock clock;
  io::DiskFileReader files;
  std::atomic<bool> flag{interrupted};
  Context ctx{out, err, clock, files, false, &flag, nullptr};
  args.insert(args.begin(), "seqc");
  std::vector<const char*> argv;
  for (const std::string& a : args) argv.push_back(a.c_str());
  SeqcRun r;
  r.status = run(static_cast<int>(argv.size()), argv.data(), ctx);
  r.out = out.str();
  r.err = err.str();
  r.clock_end = clock.now();
  fs::current_path(before);
  return r;
}

TEST(RaspblockCli, CompileHexIsTheHandWrittenStream) {
  SeqcRun r = seqc({"compile", "tests/golden/raspblock/small.yaml", "--emit", "hex"});
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err, "");
  EXPECT_EQ(r.out, slurp(kGolden / "small.hex"));
}

TEST(RaspblockCli, MistakesAreAllReportedLikeACompiler) {
  SeqcRun r = seqc({"check", "tests/golden/raspblock/mistakes.yaml"});
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.err, slurp(kGolden / "mistakes.stderr"));
  EXPECT_EQ(r.out, "tests/golden/raspblock/mistakes.yaml: 9 errors\n");
}

TEST(RaspblockCli, TheExampleDanceChecksCleanly) {
  SeqcRun r = seqc({"check", "--strict", "examples/car-dance.yaml"});
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err, "");
  EXPECT_EQ(r.out, "examples/car-dance.yaml: ok (393 packets, 16.5 s)\n");
}

TEST(RaspblockCli, SimulateCompareSaysTheCarIsNotCompared) {
  SeqcRun r = seqc({"simulate", "tests/golden/raspblock/small.yaml", "--compare"});
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("seqc: note: tests/golden/raspblock/small.yaml: --compare measures a servo "
                       "controller's fitted actions against their curves; the car's packets are "
                       "not compared"),
            std::string::npos)
      << r.err;
  // Without --compare, no such note.
  EXPECT_EQ(seqc({"simulate", "tests/golden/raspblock/small.yaml"}).err.find("--compare"),
            std::string::npos);
}

TEST(RaspblockCli, PlayToTheBuiltInEmulator) {
  SeqcRun r = seqc({"play", "tests/golden/raspblock/small.yaml", "--port", "emu:raspblock"});
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(r.err, slurp(kGolden / "play-emu.stderr"));
  EXPECT_EQ(r.clock_end, std::chrono::milliseconds(2400));  // the stream's length, not waited
}

TEST(RaspblockCli, InterruptedPlaySendsTheStop) {
  SeqcRun r = seqc({"play", "tests/golden/raspblock/small.yaml", "--port", "emu:raspblock"}, true);
  EXPECT_EQ(r.status, 130);
  EXPECT_EQ(r.err,
            "seqc: playing tests/golden/raspblock/small.yaml on emu:raspblock: 9 frames over "
            "2.4 s; Ctrl-C stops the car\n"
            "seqc: interrupted after 0 of 9 frames; sent the stop (all speeds 0)\n"
            "seqc: emu:raspblock received 1 packets, 0 rejected\n");
}

TEST(RaspblockCli, PlayNeedsAPortAndASerialOne) {
  SeqcRun none = seqc({"play", "tests/golden/raspblock/small.yaml"});
  EXPECT_EQ(none.status, 2);
  EXPECT_EQ(none.err,
            "seqc: error: name the board's serial port with --port, e.g. --port /dev/ttyAMA0 or "
            "--port ttyUSB0 (the board does not announce itself)\n"
            "  hint: --port emu:raspblock plays to the built-in board emulator\n");
  SeqcRun hid = seqc({"play", "tests/golden/raspblock/small.yaml", "--port", "hid"});
  EXPECT_EQ(hid.status, 2);
  EXPECT_EQ(hid.err,
            "seqc: error: --port hid is a USB HID device (the xArm's link); the Raspblock board "
            "is reached over a serial port at 115200 baud\n");
  SeqcRun xarm = seqc({"play", "tests/golden/raspblock/small.yaml", "--port", "emu:xarm"});
  EXPECT_EQ(xarm.status, 2);
  EXPECT_EQ(xarm.err,
            "seqc: error: --port emu:xarm is the servo controller's emulator; "
            "tests/golden/raspblock/small.yaml is for the raspblock (use --port emu:raspblock)\n");
  SeqcRun missing =
      seqc({"play", "tests/golden/raspblock/small.yaml", "--port", "/nonexistent/tty"});
  EXPECT_EQ(missing.status, 3) << missing.err;
}

TEST(RaspblockCli, UploadExplanationForABoardWithoutStorage) {
  io::DiskFileReader files;
  const std::string small = (kGolden / "small.yaml").string();
  auto car = compiler::compile_file(small, files);
  std::ostringstream err;
  EXPECT_TRUE(explain_no_storage(car, "small.yaml", err));
  EXPECT_EQ(err.str(),
            "seqc: error: small.yaml is for the Raspblock board, which has no storage: it cannot "
            "keep a sequence to run later, only follow one streamed to it live\n"
            "  hint: play it with `seqc play small.yaml --port PORT` (e.g. --port /dev/ttyAMA0)\n");
  auto arm = compiler::compile_file((kSource / "tests/data/walk-joints.yaml").string(), files);
  std::ostringstream none;
  EXPECT_FALSE(explain_no_storage(arm, "walk.yaml", none));
  EXPECT_EQ(none.str(), "");
}

}  // namespace
}  // namespace seqc::cli
