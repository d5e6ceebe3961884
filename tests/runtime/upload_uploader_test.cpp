// The uploader against a scripted controller, one fault at a time, in emulated time. Each test
// asserts what the controller stored and what the uploader reported.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>

#include "tests/runtime/upload_test_util.hpp"

namespace seqc::upload {
namespace {

using namespace std::chrono_literals;

TEST(Uploader, CleanUploadSendsExactlyProbeStopBarrierPlanBarrier) {
  Outcome o = run_upload({});
  ASSERT_EQ(o.result.status, UploadStatus::Completed) << o.result.message;
  expect_consistent(o);
  EXPECT_EQ(o.result.retries, 0);
  EXPECT_EQ(o.result.restarts, 0);
  EXPECT_EQ(o.result.battery_mv, 7400);
  EXPECT_EQ(o.busy_dropped, 0u);
  std::vector<lsc::Frame> expected{frame_of(lsc::GetBatteryVoltage{}), frame_of(lsc::GroupStop{}),
                                   frame_of(lsc::GetBatteryVoltage{})};
  const auto plan = lsc::plan_group_download(0, o.actions).value();
  for (const auto& r : plan) expected.push_back(frame_of(r));
  expected.push_back(frame_of(lsc::GetBatteryVoltage{}));
  EXPECT_EQ(o.received, expected);
  EXPECT_FALSE(o.result.run_sent);
}

TEST(Uploader, RunIsSentOnlyAfterTheFinalBarrier) {
  UploadOptions opt;
  opt.group = 3;
  opt.run = true;
  opt.run_times = 2;
  Outcome o = run_upload({}, 10, opt);
  ASSERT_EQ(o.result.status, UploadStatus::Completed) << o.result.message;
  expect_consistent(o);
  ASSERT_GE(o.received.size(), 4u);
  const std::size_t n = o.received.size();
  EXPECT_EQ(o.received[n - 4], frame_of(lsc::GroupDownloadClose{3}));
  EXPECT_EQ(o.received[n - 3], frame_of(lsc::GetBatteryVoltage{}));
  EXPECT_EQ(o.received[n - 2], frame_of(lsc::GroupRun{3, 2}));
  EXPECT_EQ(o.received[n - 1], frame_of(lsc::GetBatteryVoltage{}));
  EXPECT_TRUE(o.result.run_sent);
  EXPECT_TRUE(o.result.run_reported);
}

TEST(Uploader, PlanForAnotherGroupSendsNothing) {
  io::ManualClock clock;
  FakeController device(clock, {});
  ControllerLink link(device, clock);
  UploadOptions opt;
  opt.group = 1;
  Uploader uploader(link, opt);
  auto actions = make_actions(3);
  UploadResult r = uploader.upload(lsc::plan_group_download(2, actions).value());
  EXPECT_EQ(r.status, UploadStatus::BadPlan);
  EXPECT_EQ(r.group_state, GroupState::Unchanged);
  EXPECT_TRUE(device.received().empty());
}

TEST(Uploader, DroppedActionFrameIsResentThenBarrier) {
  FakeScript s;
  s.drop = {k1020.action(10)};
  Outcome o = run_upload(s);
  ASSERT_EQ(o.result.status, UploadStatus::Completed) << o.result.message;
  expect_consistent(o);
  EXPECT_EQ(o.result.retries, 1);
  EXPECT_EQ(o.result.restarts, 0);
  // The re-send, then the barrier before action 11.
  const auto plan = lsc::plan_group_download(0, o.actions).value();
  const std::size_t i = k1020.action(10) - 1;  // 0-based index into received
  EXPECT_EQ(o.received[i], frame_of(plan[6 + 10]));
  EXPECT_EQ(o.received[i + 1], frame_of(plan[6 + 10]));
  EXPECT_EQ(o.received[i + 2], frame_of(lsc::GetBatteryVoltage{}));
  EXPECT_EQ(o.received[i + 3], frame_of(plan[6 + 11]));
}

TEST(Uploader, LostAckIsRecoveredByResendingTheRepeat) {
  FakeScript s;
  s.corrupt = {{k1020.action(500), 0}};  // header broken: the ack is garbage
  Outcome o = run_upload(s);
  ASSERT_EQ(o.result.status, UploadStatus::Completed) << o.result.message;
  expect_consistent(o);
  EXPECT_EQ(o.result.retries, 1);
  EXPECT_EQ(o.result.restarts, 0);
  EXPECT_GT(o.result.link.garbage_bytes, 0u);
}

TEST(Uploader, CorruptedStatusByteIsNotTakenForARefusal) {
  FakeScript s;
  s.corrupt = {{k1020.action(7), 5}};  // 04 00 -> 04 ff
  Outcome o = run_upload(s);
  ASSERT_EQ(o.result.status, UploadStatus::Completed) << o.result.message;
  expect_consistent(o);
  EXPECT_EQ(o.result.restarts, 0);
  EXPECT_EQ(o.result.retries, 1);
}

TEST(Uploader, CorruptedStepByteIsIgnored) {
  FakeScript s;
  s.corrupt = {{k1020.action(7), 4}};  // 04 00 -> fb 00
  Outcome o = run_upload(s);
  ASSERT_EQ(o.result.status, UploadStatus::Completed) << o.result.message;
  expect_consistent(o);
  EXPECT_EQ(o.result.restarts, 0);
  EXPECT_EQ(o.result.retries, 1);
}

TEST(Uploader, LateAckWithinTheMarginIsJustWaitedFor) {
  FakeScript s;
  s.late = {{k1020.action(3), 300ms}};
  Outcome o = run_upload(s);
  ASSERT_EQ(o.result.status, UploadStatus::Completed) << o.result.message;
  expect_consistent(o);
  EXPECT_EQ(o.result.retries, 0);
}

TEST(Uploader, LateAckBeyondTheMarginNeverShiftsTheUpload) {
  // The ack of action 3 comes after its deadline; the re-send is re-acked at once, and the
  // late ack arrives later, in the middle of other actions, out of order.
  FakeScript s;
  s.late = {{k1020.action(3), 700ms}};
  Outcome o = run_upload(s);
  ASSERT_EQ(o.result.status, UploadStatus::Completed) << o.result.message;
  expect_consistent(o);
  EXPECT_GE(o.result.retries, 1);
  EXPECT_GE(o.result.stale_acks, 1u);
}

TEST(Uploader, LateStep1AckWhileFlashIsErased) {
  FakeScript s;
  s.erase_busy = 4s;  // longer than the step-1 margin: the re-send arrives while busy
  Outcome o = run_upload(s, 300);
  ASSERT_EQ(o.result.status, UploadStatus::Completed) << o.result.message;
  expect_consistent(o);
  EXPECT_EQ(o.busy_dropped, 1u);
  EXPECT_EQ(o.result.retries, 1);
  EXPECT_EQ(o.result.restarts, 0);
}

TEST(Uploader, DuplicateAckArrivingWithTheOriginalIsDrained) {
  FakeScript s;
  s.duplicate = {k1020.action(0), k1020.action(254), k1020.action(255), k1020.step1() + 1};
  Outcome o = run_upload(s);
  ASSERT_EQ(o.result.status, UploadStatus::Completed) << o.result.message;
  expect_consistent(o);
  EXPECT_EQ(o.result.restarts, 0);
  EXPECT_EQ(o.result.stale_acks, 4u);
  EXPECT_EQ(o.busy_dropped, 0u);
}

TEST(Uploader, DuplicateAckOnTheWireIsToldApartByItsTiming) {
  // At 9600 baud the duplicate comes 6 bytes after the original, while the next frame is
  // still on its way: it cannot be that frame's ack.
  FakeScript s;
  s.seconds_per_byte = 10.0 / 9600;
  s.duplicate = {k1020.action(0), k1020.action(40), k1020.action(41), k1020.step5()};
  Outcome o = run_upload(s);
  for (const auto& n : o.notes) std::printf("note: %s\n", n.c_str());
  ASSERT_EQ(o.result.status, UploadStatus::Completed) << o.result.message;
  expect_consistent(o);
  EXPECT_EQ(o.result.restarts, 0);
  EXPECT_EQ(o.result.stale_acks, 4u);
}

TEST(Uploader, DuplicateOfTheCloseAckAfterTheBarrierRestarts) {
  // A duplicate that shows up inside the final barrier means pairing cannot be confirmed.
  FakeScript s;
  s.duplicate = {Numbers{1, 10}.step5()};
  s.duplicate_gap = 1ms;
  Outcome o = run_upload(s, 10);
  ASSERT_EQ(o.result.status, UploadStatus::Completed) << o.result.message;
  expect_consistent(o);
  EXPECT_EQ(o.result.restarts, 1);
}

TEST(Uploader, DuplicateTakenForTheNextAckEndsInARestart) {
  // The known limit: with no wire timing to go on, a duplicate arriving after the next frame
  // was sent is taken for its ack; the frame after is dropped by the busy controller and the
  // one after that is refused for the gap. Never a shifted group: the refusal restarts the
  // download from step 1, which then completes.
  FakeScript s;
  s.duplicate = {k1020.action(20)};
  s.duplicate_gap = 1ms;
  Outcome o = run_upload(s);
  expect_completed_after(o, 1);
  EXPECT_EQ(o.busy_dropped, 1u);
}

TEST(Uploader, GapRefusalWithoutRestartsLeftEndsAsARefusal) {
  FakeScript s;
  s.duplicate = {k1020.action(20)};
  s.duplicate_gap = 1ms;
  UploadOptions options;
  options.restarts = 0;
  Outcome o = run_upload(s, 1020, options);
  expect_consistent(o);
  EXPECT_EQ(o.result.status, UploadStatus::Refused) << o.result.message;
  EXPECT_EQ(o.result.group_state, GroupState::Empty);
  EXPECT_FALSE(o.stored.has_value());
}

}  // namespace
}  // namespace seqc::upload
