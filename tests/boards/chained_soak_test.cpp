// The fault soak over a chained dance: 3,000 actions cut into three groups (1,020, 1,020 and
// 960; tests/compiler/chain_test.cpp works the cut out by hand) stored by the real uploader in
// the emulated controller under a seeded mix of faults (frames lost, late, answered twice, a
// busy controller, a reset), then started by the computer on their bar lines, in emulated time.
// Whatever the faults, a chained run either stores every group exactly as cut and starts them
// in order, each exactly on its bar line (510 s apart), or starts none: no GroupRun ever
// follows a group that was not stored. Byte flips are left out here: a flipped action can be
// stored wrong without any reply showing it (tests/runtime/upload_soak_test.cpp measures that).
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "runtime/boards/resync_run.hpp"
#include "runtime/boards/upload_run.hpp"
#include "runtime/emulator/emulator_transport.hpp"
#include "runtime/emulator/xarm_emulator.hpp"
#include "tests/compiler/lang_test_util.hpp"

namespace seqc::boards {
namespace {

using namespace std::chrono_literals;

compiler::CompileOutput three_thousand_moves() {
  compiler::testing::MemoryFiles files;
  files.files["long.yaml"] =
      "robot: xarm\ntempo: 120\nmeter: 4/4\nsequence:\n  - repeat: 1500\n    do:\n"
      "      - move: {base: 300, claw: 400}\n        time: 1b\n"
      "      - move: {base: 700, claw: 600}\n        time: 1b\n";
  compiler::CompileOptions options;
  options.chain = true;
  return compiler::compile_file("long.yaml", files, options);
}

TEST(ChainedSoak, EveryGroupStoredAsCutAndStartedOnItsBarOrNoneStarted) {
  const compiler::CompileOutput dance = three_thousand_moves();
  ASSERT_NE(dance.servo_program(), nullptr) << compiler::testing::diagnostics_of(dance);
  const ResyncCut cut = cut_for_resync(*dance.servo_program(), 0, 0, 4);
  ASSERT_TRUE(cut.fits()) << cut.error;
  ASSERT_EQ(cut.pieces.size(), 3u);
  const Board& board = *find_board("xarm");
  std::size_t completed = 0, retries = 0, restarts = 0;
  const std::size_t runs = 24;
  for (std::size_t i = 0; i < runs; ++i) {
    SCOPED_TRACE(i);
    emu::XArmConfig config;
    config.baud = i % 2 == 0 ? 0 : 115200;
    config.faults.seed = 7000 + i;
    config.faults.drop = 0.002;
    config.faults.late_ack = 0.002;
    config.faults.duplicate_ack = 0.002;
    config.faults.busy = 0.002;
    if (i % 3 == 0) config.faults.reset_at = 1 + (i * 577) % 3000;
    emu::XArmEmulator controller(config);
    io::ManualClock clock;
    emu::EmulatorTransport transport(controller, clock);
    const Line line{transport, clock};
    upload::UploadOptions options;
    options.retries = 4;
    ResyncRun r = store_pieces(board, line, dance, cut.pieces, 4, options, nullptr);
    start_pieces(board, line, cut.pieces, 4, options, r);
    for (const upload::UploadResult& u : r.uploads) {
      retries += static_cast<std::size_t>(u.retries);
      restarts += static_cast<std::size_t>(u.restarts);
    }
    // The GroupRun frames the controller took, in order, with when they arrived.
    std::vector<std::pair<int, io::TimePoint>> runs_seen;
    for (const emu::ReceivedFrame& f : controller.received()) {
      if (f.raw.size() == 7 && f.raw[3] == 0x06) runs_seen.emplace_back(f.raw[4], f.at);
    }
    if (!r.stored()) {
      EXPECT_TRUE(runs_seen.empty()) << "a group was started though the chain was not stored";
      continue;
    }
    ++completed;
    for (std::size_t k = 0; k < 3; ++k) {
      const auto stored = controller.stored_group(static_cast<std::uint8_t>(4 + k));
      ASSERT_TRUE(stored.has_value()) << k;
      ASSERT_EQ(stored->size(), cut.pieces[k].keyframes.size()) << k;
      for (std::size_t a = 0; a < stored->size(); ++a) {
        ASSERT_EQ((*stored)[a].time_ms, cut.pieces[k].keyframes[a].time_ms) << k << " " << a;
        ASSERT_EQ((*stored)[a].servos, cut.pieces[k].keyframes[a].targets) << k << " " << a;
      }
    }
    ASSERT_EQ(runs_seen.size(), 3u);
    for (std::size_t k = 0; k < 3; ++k) {
      EXPECT_EQ(runs_seen[k].first, static_cast<int>(4 + k));
      // 255 bars of 2 s between starts (a start is GroupStop and GroupRun in one write, so each
      // GroupRun arrives the same time after its own instant).
      EXPECT_EQ(runs_seen[k].second - runs_seen[0].second,
                std::chrono::duration_cast<io::Duration>(510s * static_cast<int>(k)));
    }
  }
  std::printf(
      "chained soak: %zu of %zu runs stored and started every group (%zu re-sends, %zu "
      "restarts)\n",
      completed, runs, retries, restarts);
  EXPECT_GE(completed, runs - 1);
  EXPECT_GT(retries, 0u);  // the faults did happen
  EXPECT_GT(restarts, 0u);
}

}  // namespace
}  // namespace seqc::boards
