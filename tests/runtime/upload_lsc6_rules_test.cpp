// Each recovery rule of the LSC-6 uploader (lsc6_uploader.hpp), pinned by the path it takes
// against a scripted board: the events reported (re-sends, restarts with their reasons,
// notes), the counters, and the commands the board received.
//
// The plan is three actions for group 2. Request numbers as the board counts them: 1 Stop,
// 2-4 actions 1-3 (index 0-2), then Run. On this unpaced link the deadlines are the margins:
// 0.5 s, plus 2 s for index 0 and 1 s for the last index.
#include <gtest/gtest.h>

#include <atomic>
#include <functional>
#include <string>
#include <vector>

#include "runtime/upload/lsc6_uploader.hpp"
#include "tests/runtime/upload_lsc6_fake_board.hpp"
#include "tests/runtime/upload_test_util.hpp"

namespace seqc::upload {
namespace {

using namespace std::chrono_literals;
using testing::FakeLsc6Board;
using testing::Lsc6Script;
using Lines = std::vector<std::string>;

struct Lsc6Upload {
  io::ManualClock clock;
  std::atomic<bool> interrupted{false};
  Events events;
  UploadResult result;
  std::vector<std::uint8_t> commands;

  void go(Lsc6Script script, UploadOptions options = {}, std::size_t interrupt_at = 0) {
    FakeLsc6Board board(clock, std::move(script));
    board.on_request = [&](std::size_t n) {
      if (n == interrupt_at) interrupted = true;
    };
    Lsc6Link link(board, clock, &interrupted);
    options.group = 2;
    const std::vector<lsc6::DownloadAction> plan{
        {2, 3, 0, 500, {{1, 1000}, {6, 2000}}},
        {2, 3, 1, 300, {{3, 600}}},
        {2, 3, 2, 200, {{1, 1000}, {3, 600}, {6, 2000}}},
    };
    result = upload_lsc6(link, plan, options, &events);
    commands = board.commands();
  }
};

constexpr std::uint8_t kStop = 0x07, kDownload = 0x19, kRun = 0x06;

// After a re-send, the answer still owed to the first sending is waited for and discarded
// before the next frame goes out.
TEST(Lsc6UploadRules, AnAnswerOwedAfterAResendIsAwaitedAndDiscarded) {
  Lsc6Script s;
  s.late = {{3, 700ms}};  // action 2's answer comes 0.2 s after its deadline
  Lsc6Upload u;
  u.go(s);
  ASSERT_EQ(u.result.status, UploadStatus::Completed) << u.result.message;
  EXPECT_EQ(u.events.lines, (Lines{"retry action 2 of 3 2/5: no answer within 0.500 s",
                                   "note: discarded a late answer to action 2 of 3"}));
  EXPECT_EQ(u.result.retries, 1);
  EXPECT_EQ(u.result.restarts, 0);
  EXPECT_EQ(u.result.stale_acks, 1u);
  EXPECT_EQ(u.commands,
            (std::vector<std::uint8_t>{kStop, kDownload, kDownload, kDownload, kDownload}));
}

// An answer that arrives when none is owed shows that pairing was off: restart from index 0.
TEST(Lsc6UploadRules, AnAnswerNoFrameWasOwedRestartsFromIndex0) {
  Lsc6Script s;
  s.duplicate = {3};  // action 2 is answered twice
  Lsc6Upload u;
  u.go(s);
  ASSERT_EQ(u.result.status, UploadStatus::Completed) << u.result.message;
  EXPECT_EQ(u.events.lines,
            (Lines{"restart 2/4: an answer arrived that no frame was owed (before action 3 of "
                   "3)"}));
  EXPECT_EQ(u.result.restarts, 1);
  EXPECT_EQ(u.result.retries, 0);
  EXPECT_EQ(u.result.stale_acks, 1u);
  // Stop, actions 1-2, then all three again.
  EXPECT_EQ(u.commands, (std::vector<std::uint8_t>{kStop, kDownload, kDownload, kDownload,
                                                   kDownload, kDownload}));
}

// A frame no re-send got through restarts the download from index 0.
TEST(Lsc6UploadRules, AFrameNoResendGotThroughRestartsFromIndex0) {
  Lsc6Script s;
  s.drop = {3, 4, 5, 6, 7};  // action 2, all five sendings
  Lsc6Upload u;
  u.go(s);
  ASSERT_EQ(u.result.status, UploadStatus::Completed) << u.result.message;
  EXPECT_EQ(u.events.lines,
            (Lines{"retry action 2 of 3 2/5: no answer within 0.500 s",
                   "retry action 2 of 3 3/5: no answer within 0.500 s",
                   "retry action 2 of 3 4/5: no answer within 0.500 s",
                   "retry action 2 of 3 5/5: no answer within 0.500 s",
                   "restart 2/4: the board did not answer action 2 of 3 (5 attempts, 0.500 s "
                   "each)"}));
  EXPECT_EQ(u.result.retries, 4);
  EXPECT_EQ(u.result.restarts, 1);
}

// Run is sent only after every action was answered: never after a failed download.
TEST(Lsc6UploadRules, AFailedDownloadIsNeverRun) {
  Lsc6Script s;
  s.silent_after = 2;  // action 1 is answered, then nothing
  UploadOptions options;
  options.run = true;
  options.retries = 1;
  options.restarts = 0;
  Lsc6Upload u;
  u.go(s, options);
  EXPECT_EQ(u.result.status, UploadStatus::NoAck);
  EXPECT_EQ(u.result.message,
            "the board did not answer action 2 of 3 (2 attempts, 0.500 s each); gave up after 1 "
            "attempts");
  EXPECT_FALSE(u.result.run_sent);
  EXPECT_FALSE(u.result.stop_sent);
  EXPECT_EQ(u.result.group_state, GroupState::OldCount);
  EXPECT_EQ(u.commands, (std::vector<std::uint8_t>{kStop, kDownload, kDownload, kDownload}));
}

TEST(Lsc6UploadRules, AnInterruptedDownloadIsNeverRun) {
  UploadOptions options;
  options.run = true;
  Lsc6Upload u;
  u.go({}, options, /*interrupt_at=*/3);
  EXPECT_EQ(u.result.status, UploadStatus::Interrupted);
  EXPECT_FALSE(u.result.run_sent);
  EXPECT_FALSE(u.result.stop_sent);
  EXPECT_EQ(u.commands, (std::vector<std::uint8_t>{kStop, kDownload, kDownload}));
}

// Ctrl-C while Run's answer is awaited: the group is stored, but the robot must not move, so
// Stop follows.
TEST(Lsc6UploadRules, InterruptAfterRunSendsStop) {
  UploadOptions options;
  options.run = true;
  Lsc6Upload u;
  u.go({}, options, /*interrupt_at=*/5);
  EXPECT_EQ(u.result.status, UploadStatus::Interrupted);
  EXPECT_EQ(u.result.message, "interrupted after starting group 2");
  EXPECT_TRUE(u.result.run_sent);
  EXPECT_TRUE(u.result.stop_sent);
  EXPECT_EQ(u.result.group_state, GroupState::Stored);
  EXPECT_EQ(u.commands,
            (std::vector<std::uint8_t>{kStop, kDownload, kDownload, kDownload, kRun, kStop}));
}

}  // namespace
}  // namespace seqc::upload
