// The uploader against a scripted controller when the controller refuses, falls silent, hangs
// up or the user interrupts, in emulated time. Each test asserts what the controller stored and
// what the uploader reported.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>

#include "tests/runtime/upload_test_util.hpp"

namespace seqc::upload {
namespace {

using namespace std::chrono_literals;

TEST(Uploader, RefusalIsConfirmedOnceThenFatal) {
  FakeScript s;
  s.refuse = {k1020.step1(), k1020.step1() + 2};  // step 1, barrier, step 1 again
  Outcome o = run_upload(s);
  expect_consistent(o);
  EXPECT_EQ(o.result.status, UploadStatus::Refused);
  EXPECT_EQ(o.result.restarts, 0);
  EXPECT_EQ(o.result.group_state, GroupState::Unchanged);
  EXPECT_NE(o.result.message.find("refused step 1"), std::string::npos) << o.result.message;
  EXPECT_LT(o.result.elapsed, 2s);
}

TEST(Uploader, RefusalMidwayRestartsFromStep1) {
  // A controller that reset mid-download refuses the next frame (no download is open); the
  // same frame is not refused in the fresh attempt.
  FakeScript s;
  const std::size_t a = k1020.action(100);
  s.refuse = {a, a + 2};
  Outcome o = run_upload(s);
  expect_completed_after(o, 1);
}

TEST(Uploader, RefusalMidwayWithoutRestartsLeftLeavesTheGroupEmpty) {
  FakeScript s;
  const std::size_t a = k1020.action(100);
  s.refuse = {a, a + 2};
  UploadOptions options;
  options.restarts = 0;
  Outcome o = run_upload(s, 1020, options);
  expect_consistent(o);
  EXPECT_NE(o.result.message.find("it may have restarted"), std::string::npos) << o.result.message;
  EXPECT_EQ(o.result.status, UploadStatus::Refused);
  EXPECT_EQ(o.result.group_state, GroupState::Empty);
  EXPECT_EQ(o.result.actions_acknowledged, 100u);
  EXPECT_FALSE(o.stored.has_value());
  EXPECT_EQ(describe_group_state(o.result.group_state, 0),
            "group 0 is now empty (the controller erased it; it only becomes valid when a "
            "download completes)");
}

TEST(Uploader, SilenceFromTheStartIsNoAnswer) {
  FakeScript s;
  s.silent_after = 0;
  Outcome o = run_upload(s);
  EXPECT_EQ(o.result.status, UploadStatus::NoAnswer);
  EXPECT_EQ(o.result.group_state, GroupState::Unchanged);
  // 1 + 4 re-sends of the probe, then the LSC-6 question (uploader.hpp): a DownloadAction (19)
  // into group 0, total 1, index 255, no servos, 0 ms; nothing else.
  ASSERT_EQ(o.received.size(), 6u);
  EXPECT_EQ(o.received[5], (lsc::Frame{0x19, Bytes{0x00, 0x01, 0xff, 0x00, 0x00, 0x00}}));
  EXPECT_NE(o.result.message.find("no reply from a controller on fake controller"),
            std::string::npos);
}

TEST(Uploader, SilenceMidwayFailsAfterTheRetries) {
  FakeScript s;
  s.silent_after = k1020.action(50) - 1;  // actions 0..49 are answered
  Outcome o = run_upload(s);
  expect_consistent(o);
  // Four re-sends of the action, then the restart's barrier: four more, and it gives up.
  EXPECT_EQ(o.result.status, UploadStatus::NoAck);
  EXPECT_EQ(o.result.group_state, GroupState::Empty);
  EXPECT_EQ(o.result.actions_acknowledged, 50u);
  EXPECT_EQ(o.result.retries, 8);
  EXPECT_EQ(o.result.restarts, 1);
  EXPECT_NE(o.result.message.find("stopped answering"), std::string::npos) << o.result.message;
}

TEST(Uploader, SilenceAfterStep1WasSentIsReportedAsPossiblyErased) {
  FakeScript s;
  s.silent_after = 3;
  Outcome o = run_upload(s);
  EXPECT_EQ(o.result.status, UploadStatus::NoAck);
  EXPECT_EQ(o.result.group_state, GroupState::MaybeErased);
}

TEST(Uploader, HangUpEndsAtOnce) {
  FakeScript s;
  s.hangup_at = k1020.action(200);
  Outcome o = run_upload(s);
  expect_consistent(o);
  EXPECT_EQ(o.result.status, UploadStatus::HangUp);
  EXPECT_EQ(o.result.group_state, GroupState::Empty);
  EXPECT_EQ(o.result.retries, 0);
  EXPECT_FALSE(o.stored.has_value());
}

TEST(Uploader, HangUpBeforeStep1LeavesTheGroupUnchanged) {
  FakeScript s;
  s.hangup_at = 2;
  Outcome o = run_upload(s);
  EXPECT_EQ(o.result.status, UploadStatus::HangUp);
  EXPECT_EQ(o.result.group_state, GroupState::Unchanged);
}

TEST(Uploader, InterruptBetweenFrames) {
  const std::size_t a = k1020.action(30);
  Outcome o = run_upload({}, 1020, {}, [a](FakeController& d, std::atomic<bool>& flag) {
    d.on_request = [a, &flag](std::size_t n) {
      if (n == a) flag = true;
    };
  });
  expect_consistent(o);
  EXPECT_EQ(o.result.status, UploadStatus::Interrupted);
  EXPECT_EQ(o.result.group_state, GroupState::Empty);
  EXPECT_EQ(o.received.size(), a);  // nothing after the frame during which it came
}

TEST(Uploader, InterruptInsideAWaitEndsWithinOneSlice) {
  const std::size_t a = k1020.action(30);
  io::ManualClock clock;
  FakeScript s;
  s.drop = {a};  // the uploader waits for an ack that will not come
  FakeController device(clock, s);
  std::atomic<bool> flag{false};
  io::TimePoint raised{0};
  device.on_request = [&](std::size_t n) {
    if (n == a) {
      flag = true;
      raised = clock.now();
    }
  };
  ControllerLink link(device, clock, &flag);
  Uploader uploader(link, {});
  auto actions = make_actions(1020);
  UploadResult r = uploader.upload(lsc::plan_group_download(0, actions).value());
  EXPECT_EQ(r.status, UploadStatus::Interrupted);
  EXPECT_LE(clock.now() - raised, 100ms);
  EXPECT_EQ(device.received().size(), a);
}

TEST(Uploader, DeadlinesFollowTheWire) {
  io::ManualClock clock;
  FakeScript s;
  s.seconds_per_byte = 0.001;
  FakeController device(clock, s);
  ControllerLink link(device, clock);
  UploadOptions opt;
  opt.reply_margin = 100ms;
  opt.open_margin = 2s;
  Uploader uploader(link, opt);
  EXPECT_EQ(uploader.reply_timeout(29, 6, false), 135ms);
  EXPECT_EQ(uploader.reply_timeout(8, 6, true), 2014ms);
}

TEST(Uploader, GroupStateSentences) {
  EXPECT_EQ(describe_group_state(GroupState::Unchanged, 2), "group 2 is unchanged");
  EXPECT_EQ(describe_group_state(GroupState::MaybeErased, 2),
            "group 2 is unchanged, unless the controller acted on the opening frame it never "
            "acknowledged (then it is empty)");
  EXPECT_EQ(describe_group_state(GroupState::Uncertain, 2),
            "group 2 holds what the controller stored last, which may not match the file; "
            "upload again");
}

}  // namespace
}  // namespace seqc::upload
