// The uploader against a scripted controller, one fault at a time, in emulated time. Each test
// asserts what the controller stored and what the uploader reported.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>

#include "runtime/protocol/group_download.hpp"
#include "runtime/upload/uploader.hpp"
#include "tests/runtime/upload_fake_controller.hpp"

namespace seqc::upload {
namespace {

using testing::FakeController;
using testing::FakeScript;
using namespace std::chrono_literals;

std::vector<lsc::GroupAction> make_actions(std::size_t n, std::uint8_t servos = 6) {
  std::vector<lsc::GroupAction> actions;
  for (std::size_t i = 0; i < n; ++i) {
    lsc::GroupAction a;
    a.time_ms = static_cast<std::uint16_t>(20 + i % 500);
    for (std::uint8_t s = 1; s <= servos; ++s) {
      a.servos.push_back({s, static_cast<std::uint16_t>((i * 7 + s * 100) % 1001)});
    }
    actions.push_back(std::move(a));
  }
  return actions;
}

// Request numbers as the controller counts them: 1 probe, 2 GroupStop, 3 barrier, 4 step 1,
// then one step 2 per block, step 3, the actions, step 5, the final barrier.
struct Numbers {
  std::size_t blocks;
  std::size_t actions;
  std::size_t step1() const { return 4; }
  std::size_t action(std::size_t k) const { return 6 + blocks + k; }
  std::size_t step5() const { return action(actions); }
};

struct Outcome {
  UploadResult result;
  std::vector<lsc::GroupAction> actions;
  std::optional<std::vector<lsc::GroupAction>> stored;
  std::vector<lsc::Frame> received;
  std::size_t busy_dropped = 0;
  std::vector<std::string> notes;
};

class Recorder final : public UploadObserver {
 public:
  void on_retry(const RetryEvent& e) override { notes.push_back("retry: " + e.what); }
  void on_note(const std::string& n) override { notes.push_back(n); }
  std::vector<std::string> notes;
};

Outcome run_upload(FakeScript script, std::size_t n = 1020, UploadOptions options = {},
                   std::function<void(FakeController&, std::atomic<bool>&)> setup = {}) {
  io::ManualClock clock;
  FakeController device(clock, std::move(script));
  std::atomic<bool> interrupted{false};
  if (setup) setup(device, interrupted);
  ControllerLink link(device, clock, &interrupted);
  Recorder recorder;
  Uploader uploader(link, options, &recorder);
  Outcome out;
  out.actions = make_actions(n);
  auto plan = lsc::plan_group_download(options.group, out.actions);
  EXPECT_TRUE(plan.ok());
  out.result = uploader.upload(*plan);
  out.stored = device.stored(options.group);
  out.received = device.received();
  out.busy_dropped = device.busy_dropped();
  out.notes = recorder.notes;
  return out;
}

lsc::Frame frame_of(const lsc::Request& r) { return lsc::encode(r).value(); }

// The one property every test checks: success means the controller holds exactly the plan.
void expect_consistent(const Outcome& o) {
  if (o.result.ok()) {
    ASSERT_TRUE(o.stored.has_value());
    EXPECT_EQ(*o.stored, o.actions);
    EXPECT_EQ(o.result.group_state, GroupState::Stored);
    EXPECT_EQ(o.result.actions_acknowledged, o.actions.size());
  }
}

const Numbers k1020{4, 1020};

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

TEST(Uploader, DuplicateTakenForTheNextAckEndsSafelyAsARefusal) {
  // The known limit: with no wire timing to go on, a duplicate arriving after the next frame
  // was sent is taken for its ack; the frame after is dropped by the busy controller and the
  // one after that is refused for the gap. Never a shifted group: it ends as a refusal.
  FakeScript s;
  s.duplicate = {k1020.action(20)};
  s.duplicate_gap = 1ms;
  Outcome o = run_upload(s);
  expect_consistent(o);
  EXPECT_EQ(o.result.status, UploadStatus::Refused) << o.result.message;
  EXPECT_EQ(o.result.group_state, GroupState::Empty);
  EXPECT_FALSE(o.stored.has_value());
  EXPECT_EQ(o.busy_dropped, 1u);
}

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

TEST(Uploader, RefusalMidwayLeavesTheGroupEmpty) {
  FakeScript s;
  const std::size_t a = k1020.action(100);
  s.refuse = {a, a + 2};
  Outcome o = run_upload(s);
  expect_consistent(o);
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
  EXPECT_EQ(o.received.size(), 5u);  // 1 + 4 re-sends of the probe, nothing else
  EXPECT_NE(o.result.message.find("no reply from a controller on fake controller"),
            std::string::npos);
}

TEST(Uploader, SilenceMidwayFailsAfterTheRetries) {
  FakeScript s;
  s.silent_after = k1020.action(50) - 1;  // actions 0..49 are answered
  Outcome o = run_upload(s);
  expect_consistent(o);
  EXPECT_EQ(o.result.status, UploadStatus::NoAck);
  EXPECT_EQ(o.result.group_state, GroupState::Empty);
  EXPECT_EQ(o.result.actions_acknowledged, 50u);
  EXPECT_EQ(o.result.retries, 4);
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
