// The dry run is the real upload against a device that accepts everything, so its frames must
// be exactly what a fault-free emulated board receives from an upload. Checked for the xArm
// family and the LSC-6, with and without a run, plus the shape of the commented text.
#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "compiler/compile.hpp"
#include "runtime/boards/board.hpp"
#include "runtime/boards/dry_run.hpp"
#include "runtime/emulator/emulator_transport.hpp"
#include "runtime/emulator/lsc6_emulator.hpp"
#include "runtime/emulator/xarm_emulator.hpp"
#include "runtime/io/disk.hpp"
#include "tests/boards/board_test_util.hpp"

namespace seqc::boards {
namespace {

using test_support::compile_example;

Bytes joined(const std::vector<Bytes>& frames) {
  Bytes all;
  for (const Bytes& f : frames) all.insert(all.end(), f.begin(), f.end());
  return all;
}

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

struct Case {
  const compiler::CompileOutput output;
  const Board& board;
  Plan plan;
  explicit Case(const char* file)
      : output(compile_example(file)), board(board_for(output)), plan(planned(board, output)) {}
  static Plan planned(const Board& board, const compiler::CompileOutput& output) {
    auto p = plan_for(board, output, 0);
    EXPECT_TRUE(p.ok()) << (p ? "" : p.error().message);
    return p ? std::move(p).value() : Plan{};
  }
};

upload::UploadOptions options(bool run) {
  upload::UploadOptions o;
  o.group = 0;
  o.run = run;
  return o;
}

TEST(BoardsDryRun, XarmFramesAreWhatTheControllerReceives) {
  const Case walk("../tests/data/walk-joints.yaml");
  ASSERT_EQ(walk.board.key, "xarm");
  for (const bool run : {false, true}) {
    const DryRun dry = dry_run(walk.board, walk.plan, options(run));
    ASSERT_TRUE(dry.result.ok()) << dry.result.message;
    // Probe, GroupStop, barrier, 31 download steps, barrier; with a run GroupRun and a barrier.
    EXPECT_EQ(dry.frames.size(), run ? 37u : 35u);

    io::ManualClock clock;
    emu::XArmEmulator controller{emu::XArmConfig{}};
    emu::EmulatorTransport transport(controller, clock);
    const upload::UploadResult sent =
        upload(walk.board, Line{transport, clock}, walk.plan, options(run), nullptr);
    ASSERT_TRUE(sent.ok()) << sent.message;
    EXPECT_EQ(to_hex(joined(dry.frames)), to_hex(controller.received_bytes())) << "run " << run;
  }
}

TEST(BoardsDryRun, XarmTextCommentsEveryFrame) {
  const Case walk("../tests/data/walk-joints.yaml");
  const DryRun dry = dry_run(walk.board, walk.plan, options(true));
  const std::vector<std::string> text = lines(dry.text);
  ASSERT_EQ(text.size(), 37u);
  EXPECT_EQ(text[0], "55 55 02 0f                               # probe: GetBatteryVoltage");
  EXPECT_EQ(text[1], "55 55 02 07                               # GroupStop");
  EXPECT_EQ(text[2], "55 55 02 0f                               # barrier: GetBatteryVoltage");
  EXPECT_EQ(text[34], "55 55 02 0f                               # barrier: GetBatteryVoltage");
  EXPECT_EQ(text[35], "55 55 05 06 00 01 00                      # GroupRun group=0 times=1");
  EXPECT_EQ(text[36], "55 55 02 0f                               # barrier: GetBatteryVoltage");
}

TEST(BoardsDryRun, Lsc6FramesAreWhatTheBoardReceives) {
  const Case learm("learm.yaml");
  ASSERT_EQ(learm.board.key, "lsc6");
  for (const bool run : {false, true}) {
    const DryRun dry = dry_run(learm.board, learm.plan, options(run));
    ASSERT_TRUE(dry.result.ok()) << dry.result.message;
    // Stop, 36 DownloadActions; with a run Run.
    EXPECT_EQ(dry.frames.size(), run ? 38u : 37u);

    io::ManualClock clock;
    emu::Lsc6Emulator board{emu::Lsc6Config{}};
    emu::EmulatorTransport transport(board, clock);
    const upload::UploadResult sent =
        upload(learm.board, Line{transport, clock}, learm.plan, options(run), nullptr);
    ASSERT_TRUE(sent.ok()) << sent.message;
    EXPECT_EQ(to_hex(joined(dry.frames)), to_hex(board.received_bytes())) << "run " << run;
  }
}

TEST(BoardsDryRun, Lsc6TextCommentsEveryFrame) {
  const Case learm("learm.yaml");
  const DryRun dry = dry_run(learm.board, learm.plan, options(true));
  const std::vector<std::string> text = lines(dry.text);
  ASSERT_EQ(text.size(), 38u);
  EXPECT_EQ(text[0], "55 55 02 07                               # Stop");
  EXPECT_EQ(text[1].substr(0, 6), "55 55 ");
  EXPECT_NE(text[1].find("# DownloadAction group=0 total=36 index=0 "), std::string::npos)
      << text[1];
  EXPECT_EQ(text[37], "55 55 05 06 00 01 00                      # Run group=0 times=1");
}

TEST(BoardsDryRun, ABoardWithoutStorageHasNone) {
  const DryRun dry = dry_run(*find_board("raspblock"), Plan{}, options(false));
  EXPECT_EQ(dry.result.status, upload::UploadStatus::BadPlan);
  EXPECT_TRUE(dry.frames.empty());
}

}  // namespace
}  // namespace seqc::boards
