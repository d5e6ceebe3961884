// The LSC-6 uploader against the LSC-6 firmware emulator in emulated time: what the board
// stores (compared with actions written by hand), what it is never sent, how lost frames and
// silent boards end, and the run that some copies of the firmware never answer.
#include <gtest/gtest.h>

#include <atomic>
#include <string>
#include <vector>

#include "runtime/emulator/emulator_transport.hpp"
#include "runtime/emulator/lsc6_emulator.hpp"
#include "runtime/emulator/xarm_emulator.hpp"
#include "base/bytes.hpp"
#include "runtime/upload/lsc6_uploader.hpp"

namespace seqc::upload {
namespace {

using lsc6::DownloadAction;

// Three actions for group 2, written by hand.
std::vector<DownloadAction> three_actions(std::uint8_t group = 2) {
  return {
      {group, 3, 0, 500, {{1, 1000}, {6, 2000}}},
      {group, 3, 1, 300, {{3, 600}}},
      {group, 3, 2, 200, {{1, 1000}, {3, 600}, {6, 2000}}},
  };
}

class Lsc6Upload : public ::testing::Test {
 protected:
  UploadResult upload(emu::Lsc6Config config, const std::vector<DownloadAction>& plan,
                      UploadOptions options = {}) {
    board_ = std::make_unique<emu::Lsc6Emulator>(config);
    transport_ = std::make_unique<emu::EmulatorTransport>(*board_, clock_);
    Lsc6Link link(*transport_, clock_, &interrupted_);
    if (options.group == 0) options.group = plan.empty() ? 0 : plan.front().group;
    return upload_lsc6(link, plan, options);
  }
  // Every frame the board's receiver completed, as hex.
  std::vector<std::string> frames() const {
    std::vector<std::string> out;
    for (const auto& r : board_->received()) out.push_back(to_hex(r.raw));
    return out;
  }

  io::ManualClock clock_;
  std::atomic<bool> interrupted_{false};
  std::unique_ptr<emu::Lsc6Emulator> board_;
  std::unique_ptr<emu::EmulatorTransport> transport_;
};

TEST_F(Lsc6Upload, StoresTheActionsAndSendsNothingElse) {
  const UploadResult r = upload({}, three_actions());
  ASSERT_TRUE(r.ok()) << r.message;
  EXPECT_EQ(r.actions_acknowledged, 3u);
  EXPECT_EQ(r.group_state, GroupState::Stored);
  const auto stored = board_->stored_group(2);
  ASSERT_TRUE(stored.has_value());
  ASSERT_EQ(stored->size(), 3u);
  EXPECT_EQ((*stored)[0].time_ms, 500);
  EXPECT_EQ((*stored)[0].servos, (std::vector<lsc6::Target>{{1, 1000}, {6, 2000}}));
  EXPECT_EQ((*stored)[1].servos, (std::vector<lsc6::Target>{{3, 600}}));
  EXPECT_EQ((*stored)[2].time_ms, 200);
  // Stop first, then the three frames, byte for byte as docs/protocol/lsc-6.md lays them out.
  EXPECT_EQ(frames(), (std::vector<std::string>{
                          "55 55 02 07",
                          "55 55 0e 19 02 03 00 02 f4 01 01 e8 03 06 d0 07",
                          "55 55 0b 19 02 03 01 01 2c 01 03 58 02",
                          "55 55 11 19 02 03 02 03 c8 00 01 e8 03 03 58 02 06 d0 07",
                      }));
}

TEST_F(Lsc6Upload, LeavesTheOtherGroupsAlone) {
  // A group stored earlier survives: the uploader never sends EraseAll.
  board_ = std::make_unique<emu::Lsc6Emulator>();
  transport_ = std::make_unique<emu::EmulatorTransport>(*board_, clock_);
  Lsc6Link link(*transport_, clock_);
  UploadOptions first;
  first.group = 5;
  ASSERT_TRUE(upload_lsc6(link, three_actions(5), first).ok());
  UploadOptions second;
  second.group = 2;
  ASSERT_TRUE(upload_lsc6(link, three_actions(2), second).ok());
  EXPECT_EQ(board_->stored_count(5), 3);
  EXPECT_EQ(board_->stored_count(2), 3);
  for (const std::string& f : frames()) EXPECT_NE(f.substr(0, 11), "55 55 02 08") << f;
}

TEST_F(Lsc6Upload, LostFramesAreSentAgainAndStillStoreEveryAction) {
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    emu::Lsc6Config config;
    config.drop = 0.3;
    config.seed = seed;
    const UploadResult r = upload(config, three_actions());
    ASSERT_TRUE(r.ok()) << "seed " << seed << ": " << r.message;
    const auto stored = board_->stored_group(2);
    ASSERT_TRUE(stored.has_value()) << "seed " << seed;
    EXPECT_EQ((*stored)[1].servos, (std::vector<lsc6::Target>{{3, 600}})) << "seed " << seed;
    EXPECT_EQ((*stored)[2].servos.size(), 3u) << "seed " << seed;
  }
}

TEST_F(Lsc6Upload, NoBoardIsNoAnswer) {
  emu::Lsc6Config config;
  config.drop = 1.0;  // a board that hears nothing, like a wrong port
  UploadOptions options;
  options.retries = 1;
  options.restarts = 1;
  const UploadResult r = upload(config, three_actions(), options);
  EXPECT_EQ(r.status, UploadStatus::NoAnswer);
  EXPECT_NE(r.message.find("no answer from an LSC-6 board on emu:lsc6"), std::string::npos)
      << r.message;
  EXPECT_EQ(r.group_state, GroupState::OldCount) << "index 0 went out: it may have erased";
}

// An xArm-family controller ignores command 25 but answers the GetBatteryVoltage that follows
// the first unanswered index 0: the upload ends there, saying which dialect answered, with
// nothing stored.
TEST_F(Lsc6Upload, AnXArmControllerDoesNotAnswerTheDialect) {
  emu::XArmEmulator xarm;
  emu::EmulatorTransport transport(xarm, clock_);
  Lsc6Link link(transport, clock_);
  UploadOptions options;
  options.group = 2;
  options.retries = 0;
  options.restarts = 0;
  const UploadResult r = upload_lsc6(link, three_actions(), options);
  EXPECT_EQ(r.status, UploadStatus::OtherDialect);
  EXPECT_EQ(r.group_state, GroupState::Unchanged);
  EXPECT_EQ(link.other_dialect_replies(), 1u);
}

TEST_F(Lsc6Upload, RunIsConfirmedOrReportedUnconfirmed) {
  UploadOptions options;
  options.run = true;
  UploadResult r = upload({}, three_actions(), options);
  ASSERT_TRUE(r.ok());
  EXPECT_TRUE(r.run_sent);
  EXPECT_TRUE(r.run_reported);
  EXPECT_EQ(board_->playing_group(), 2);

  emu::Lsc6Config silent;
  silent.run_reply = false;
  r = upload(silent, three_actions(), options);
  ASSERT_TRUE(r.ok()) << "an unanswered Run is not a failure";
  EXPECT_TRUE(r.run_sent);
  EXPECT_FALSE(r.run_reported);
  EXPECT_EQ(board_->playing_group(), 2);
}

TEST_F(Lsc6Upload, RefusesAPlanForAnotherGroupBeforeSendingAnything) {
  UploadOptions options;
  options.group = 4;
  const UploadResult r = upload({}, three_actions(2), options);
  EXPECT_EQ(r.status, UploadStatus::BadPlan);
  EXPECT_TRUE(board_->received().empty());
}

TEST_F(Lsc6Upload, TakesItsTimeFromTheWireAndTheFlash) {
  const UploadResult r = upload({}, three_actions());
  ASSERT_TRUE(r.ok());
  // 4 + 16 + 13 + 19 bytes out and 3 x 4 back at 9600 baud (64 x 1.0417 ms = 66.7 ms), plus
  // four sector erases at index 0 (180 ms), three slot writes (2.1 ms) and the count table
  // (45 + 1.4 ms) = 295.2 ms; nothing else waits.
  const double ms = std::chrono::duration<double, std::milli>(r.elapsed).count();
  EXPECT_NEAR(ms, 295.2, 0.5);
}

}  // namespace
}  // namespace seqc::upload
