// Each recovery rule of the xArm uploader (uploader.hpp), pinned by the path it takes: the
// scripted controller produces exactly the situation one rule handles, and the test asserts
// every event the uploader reported (re-sends, restarts with their reasons, notes) and its
// counters, so an upload that still completes by another route fails the test.
//
// All uploads are 10 actions (one block). Request numbers as the controller counts them:
// 1 probe, 2 GroupStop, 3 barrier, 4 step 1, 5 step 2, 6 step 3, 7 + k action k (0-based),
// 17 step 5, 18 the final barrier.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <functional>
#include <string>
#include <vector>

#include "tests/runtime/upload_test_util.hpp"

namespace seqc::upload {
namespace {

using namespace std::chrono_literals;

constexpr std::size_t kStep2 = 5;
constexpr std::size_t kStep5 = 17;
constexpr std::size_t action(std::size_t k) { return 7 + k; }

struct Upload {
  io::ManualClock clock;
  std::atomic<bool> interrupted{false};
  Events events;
  UploadResult result;
  std::vector<lsc::GroupAction> actions = make_actions(10);
  std::optional<std::vector<lsc::GroupAction>> stored;
  std::vector<lsc::Frame> received;
  std::size_t busy_dropped = 0;

  void go(FakeScript script, UploadOptions options = {},
          std::function<void(FakeController&)> setup = {}) {
    FakeController device(clock, std::move(script));
    if (setup) setup(device);
    ControllerLink link(device, clock, &interrupted);
    Uploader uploader(link, options, &events);
    auto plan = lsc::plan_group_download(options.group, actions);
    ASSERT_TRUE(plan.ok());
    result = uploader.upload(*plan);
    stored = device.stored(options.group);
    received = device.received();
    busy_dropped = device.busy_dropped();
  }
  bool sent_group_run() const {
    for (const lsc::Frame& f : received) {
      if (f.cmd == 0x06) return true;
    }
    return false;
  }
};

using Lines = std::vector<std::string>;

// The late-ack guard: action 4's ack comes 700 ms late, after its 500 ms deadline. The re-send
// is acknowledged at once; the guard then waits until 1 s after the first sending and discards
// the late ack there, so it is never taken for a later frame's.
TEST(UploadRules, LateAckGuardDiscardsTheFirstSendingsAckBeforeTheNextFrame) {
  FakeScript s;
  s.late = {{action(3), 700ms}};
  Upload r;
  r.go(s);
  ASSERT_EQ(r.result.status, UploadStatus::Completed) << r.result.message;
  EXPECT_EQ(*r.stored, r.actions);
  EXPECT_EQ(r.events.lines,
            (Lines{"retry step 4 (action 4 of 10: block 0, index 3) 2/5: no acknowledgement "
                   "within 0.500 s",
                   "note: discarded a late acknowledgement: GroupDownloadAck step=4 status=0 "
                   "(accepted)"}));
  EXPECT_EQ(r.result.retries, 1);
  EXPECT_EQ(r.result.restarts, 0);
  EXPECT_EQ(r.result.stale_acks, 1u);
  EXPECT_EQ(r.busy_dropped, 0u);
  // Re-send, then (after the guard) the barrier, then action 5.
  ASSERT_GT(r.received.size(), action(3) + 2);
  EXPECT_EQ(r.received[action(3)], r.received[action(3) - 1]);
  EXPECT_EQ(r.received[action(3) + 1], (lsc::Frame{0x0f, {}}));
}

// The early-ack hold: at 9600 baud the duplicate of action 4's ack arrives 6 bytes after the
// original, while action 5 is still on the wire, so it cannot be action 5's ack. It is held;
// action 5's own ack follows and the early one is discarded.
TEST(UploadRules, AnAckSoonerThanTheWireAllowsIsHeldAndDiscarded) {
  FakeScript s;
  s.seconds_per_byte = 10.0 / 9600;
  s.duplicate = {action(3)};
  Upload r;
  r.go(s);
  ASSERT_EQ(r.result.status, UploadStatus::Completed) << r.result.message;
  EXPECT_EQ(*r.stored, r.actions);
  EXPECT_EQ(r.events.lines,
            (Lines{"note: discarded an acknowledgement that came sooner than the wire allows (a "
                   "duplicate or late one): GroupDownloadAck step=4 status=0 (accepted)"}));
  EXPECT_EQ(r.result.retries, 0);
  EXPECT_EQ(r.result.restarts, 0);
  EXPECT_EQ(r.result.stale_acks, 1u);
}

// Rule (d): a duplicate of step 2's ack arrives 3 ms late, while the uploader waits for action 1
// (step 4) outside any barrier. Pairing was off, so the download restarts from step 1; action
// 1's real ack is then absorbed by the restart's barrier (which the controller, still busy with
// action 1, dropped once).
TEST(UploadRules, AnAckOfAnEarlierStepWhileWaitingRestartsTheDownload) {
  FakeScript s;
  s.duplicate = {kStep2};
  s.duplicate_gap = 3ms;
  Upload r;
  r.go(s);
  ASSERT_EQ(r.result.status, UploadStatus::Completed) << r.result.message;
  EXPECT_EQ(*r.stored, r.actions);
  EXPECT_EQ(r.events.lines,
            (Lines{"restart 2/4: an GroupDownloadAck step=2 status=0 (accepted) while waiting "
                   "for step 4 (action 1 of 10: block 0, index 0)",
                   "note: discarded a stale acknowledgement: GroupDownloadAck step=4 status=0 "
                   "(accepted)",
                   "retry barrier (battery voltage) 2/5: no reply within 0.500 s"}));
  EXPECT_EQ(r.result.restarts, 1);
  EXPECT_EQ(r.result.retries, 1);
  EXPECT_EQ(r.result.stale_acks, 2u);
  EXPECT_EQ(r.busy_dropped, 1u);
}

// Rule (d) between frames: step 3's acknowledgement read together with the first action's
// (a stale reply queued behind it) is left for the drain before the next frame, which must
// take it as proof that an earlier pairing was wrong and restart, not ignore it.
TEST(UploadRules, AnAckOfAnEarlierStepFoundBetweenFramesRestartsTheDownload) {
  FakeScript s;
  s.trailing[action(0)] = {0x55, 0x55, 0x04, 0x05, 0x03, 0x00};  // GroupDownload step 3, 00
  Upload r;
  r.go(s);
  ASSERT_EQ(r.result.status, UploadStatus::Completed) << r.result.message;
  EXPECT_EQ(*r.stored, r.actions);
  EXPECT_EQ(r.events.lines,
            (Lines{"restart 2/4: an unexpected GroupDownloadAck step=3 status=0 (accepted) "
                   "arrived between frames"}));
  EXPECT_EQ(r.result.restarts, 1);
  EXPECT_EQ(r.result.retries, 0);
  EXPECT_EQ(r.result.stale_acks, 1u);
  // The restart began again at step 1: two step-1 frames reached the controller.
  std::size_t opens = 0;
  for (const lsc::Frame& f : r.received) {
    if (f.cmd == 0x05 && !f.data.empty() && f.data[0] == 0x01) ++opens;
  }
  EXPECT_EQ(opens, 2u);
}

// Rule (d) at the final barrier: a second ack of step 5 (not re-sent) before the barrier's
// reply means some ack was mis-paired: restart.
TEST(UploadRules, AnExtraAckAtTheFinalBarrierRestartsTheDownload) {
  FakeScript s;
  s.duplicate = {kStep5};
  s.duplicate_gap = 1ms;
  Upload r;
  r.go(s);
  ASSERT_EQ(r.result.status, UploadStatus::Completed) << r.result.message;
  EXPECT_EQ(*r.stored, r.actions);
  EXPECT_EQ(r.events.lines,
            (Lines{"note: an acknowledgement nothing was waiting for: GroupDownloadAck step=5 "
                   "status=0 (accepted)",
                   "restart 2/4: an extra GroupDownloadAck step=5 status=0 (accepted) arrived "
                   "before the barrier's reply (after step 5)"}));
  EXPECT_EQ(r.result.restarts, 1);
  EXPECT_EQ(r.result.retries, 0);
  EXPECT_EQ(r.result.stale_acks, 1u);
}

// A controller reset as action 6 arrives: the frame is lost, the re-send is refused (no
// download is open), confirmed by one more sending, and the download restarts from step 1.
TEST(UploadRules, AResetMidDownloadIsARefusalThatRestartsFromStep1) {
  FakeScript s;
  s.reset_at = action(5);
  Upload r;
  r.go(s);
  ASSERT_EQ(r.result.status, UploadStatus::Completed) << r.result.message;
  EXPECT_EQ(*r.stored, r.actions);
  const std::string a6 = "step 4 (action 6 of 10: block 0, index 5)";
  EXPECT_EQ(r.events.lines,
            (Lines{"retry " + a6 + " 2/5: no acknowledgement within 0.500 s",
                   "note: the controller refused " + a6 +
                       " (status 01); sending it once more to tell a refusal from a corrupted "
                       "acknowledgement",
                   "retry " + a6 + " 3/5: refused once (status 01)",
                   "restart 2/4: the controller refused " + a6 +
                       " (status 01, twice in a row); it may have restarted (a power dip forgets "
                       "a download), or an earlier acknowledgement was taken for the wrong "
                       "frame"}));
  EXPECT_EQ(r.result.restarts, 1);
  EXPECT_EQ(r.result.retries, 2);
}

// A frame refused twice in one attempt restarts the download; refused twice again in the next
// attempt, that is the controller's answer.
TEST(UploadRules, ARefusalRestartsOnceAndARepeatedOneIsFinal) {
  // Attempt 1: 9 action 2 (refused), 10 barrier, 11 action 2 (refused); attempt 2 starts with
  // the restart's barrier at 12, so action 2 is 18 and, after the barrier at 19, 20.
  FakeScript s;
  s.refuse = {action(2), action(2) + 2, 18, 20};
  Upload r;
  r.go(s);
  const std::string a3 = "step 4 (action 3 of 10: block 0, index 2)";
  const std::string refused_note =
      "note: the controller refused " + a3 +
      " (status 01); sending it once more to tell a refusal from a corrupted acknowledgement";
  EXPECT_EQ(r.result.status, UploadStatus::Refused);
  EXPECT_EQ(r.result.message, "the controller refused " + a3 + " (status 01, twice in a row)");
  EXPECT_EQ(r.events.lines,
            (Lines{refused_note, "retry " + a3 + " 2/5: refused once (status 01)",
                   "restart 2/4: the controller refused " + a3 +
                       " (status 01, twice in a row); it may have restarted (a power dip forgets "
                       "a download)",
                   refused_note, "retry " + a3 + " 2/5: refused once (status 01)"}));
  EXPECT_EQ(r.result.restarts, 1);
  EXPECT_EQ(r.result.group_state, GroupState::Empty);
  EXPECT_FALSE(r.stored.has_value());
}

// GroupRun is sent only after a download that completed: never after a failed one.
TEST(UploadRules, AFailedDownloadIsNeverRun) {
  FakeScript s;
  s.silent_after = action(4) - 1;  // actions 0-3 are answered, then nothing
  UploadOptions options;
  options.run = true;
  options.restarts = 0;
  Upload r;
  r.go(s, options);
  EXPECT_EQ(r.result.status, UploadStatus::NoAck);
  EXPECT_EQ(r.result.actions_acknowledged, 4u);
  EXPECT_FALSE(r.result.run_sent);
  EXPECT_FALSE(r.sent_group_run());
}

TEST(UploadRules, AnInterruptedDownloadIsNeverRun) {
  UploadOptions options;
  options.run = true;
  Upload r;
  r.go({}, options, [&](FakeController& d) {
    d.on_request = [&](std::size_t n) {
      if (n == action(6)) r.interrupted = true;
    };
  });
  EXPECT_EQ(r.result.status, UploadStatus::Interrupted);
  EXPECT_FALSE(r.result.run_sent);
  EXPECT_FALSE(r.result.stop_sent);
  EXPECT_FALSE(r.result.erase_sent);
  EXPECT_FALSE(r.sent_group_run());
  EXPECT_EQ(r.received.size(), action(6));
}

// Ctrl-C after step 5 was acknowledged, before the final barrier: GroupErase (55 55 03 08 00)
// goes out and its reply (55 55 02 08) is awaited, so the group is known to be empty.
TEST(UploadRules, InterruptAfterStep5ErasesAndWaitsForTheErasesReply) {
  Upload r;
  r.events.progress = [&](const UploadProgress& p) {
    if (p.frames_total > 0 && p.frames_done == p.frames_total) r.interrupted = true;
  };
  r.go({});
  EXPECT_EQ(r.result.status, UploadStatus::Interrupted);
  EXPECT_TRUE(r.result.erase_sent);
  EXPECT_TRUE(r.result.erase_confirmed);
  EXPECT_FALSE(r.result.stop_sent);
  EXPECT_EQ(r.result.group_state, GroupState::Empty);
  ASSERT_EQ(r.received.size(), kStep5 + 1);
  EXPECT_EQ(r.received.back(), (lsc::Frame{0x08, {0x00}}));
  EXPECT_FALSE(r.stored.has_value());
  EXPECT_TRUE(r.events.lines.empty()) << r.events.lines.front();
  // The reply came 2 ms after the erase arrived: no waiting out the deadline.
  EXPECT_LT(r.result.elapsed, 1s);
}

// The same, but the controller never answers the erase: the wait ends at step 1's deadline
// (3 s margin, no wire time on this link) and the group is not claimed to be empty.
TEST(UploadRules, AnUnansweredEraseIsReportedUnconfirmedAfterABoundedWait) {
  FakeScript s;
  s.erase_unanswered = true;
  Upload r;
  io::TimePoint raised{0};
  r.events.progress = [&](const UploadProgress& p) {
    if (p.frames_total > 0 && p.frames_done == p.frames_total) {
      r.interrupted = true;
      raised = r.clock.now();
    }
  };
  r.go(s);
  EXPECT_EQ(r.result.status, UploadStatus::Interrupted);
  EXPECT_TRUE(r.result.erase_sent);
  EXPECT_FALSE(r.result.erase_confirmed);
  EXPECT_EQ(r.result.group_state, GroupState::Uncertain);
  EXPECT_EQ(r.events.lines,
            (Lines{"note: the controller did not confirm GroupErase of group 0 within 3.000 s"}));
  EXPECT_EQ(r.clock.now() - raised, 3s);
}

// Ctrl-C as step 5 arrives: the erase reaches a controller still busy storing step 5 and is
// dropped. Without its reply the group is not reported empty: it holds the whole download.
TEST(UploadRules, AnEraseDroppedByABusyControllerIsNotTakenForDone) {
  Upload r;
  r.go({}, {}, [&](FakeController& d) {
    d.on_request = [&](std::size_t n) {
      if (n == kStep5) r.interrupted = true;
    };
  });
  EXPECT_EQ(r.result.status, UploadStatus::Interrupted);
  EXPECT_TRUE(r.result.erase_sent);
  EXPECT_FALSE(r.result.erase_confirmed);
  EXPECT_EQ(r.busy_dropped, 1u);
  EXPECT_EQ(r.result.group_state, GroupState::Uncertain);
  ASSERT_TRUE(r.stored.has_value());
  EXPECT_EQ(*r.stored, r.actions);
}

// A port that hangs up and comes back 2 s later: reopened, and the download starts over from
// the probe.
TEST(UploadRules, AHangUpIsReopenedAndTheDownloadStartsOver) {
  FakeScript s;
  s.hangup_at = action(5);
  s.back_after = 2s;
  Upload r;
  r.go(s);
  ASSERT_EQ(r.result.status, UploadStatus::Completed) << r.result.message;
  EXPECT_EQ(*r.stored, r.actions);
  EXPECT_EQ(r.events.lines,
            (Lines{"note: the port hung up; waiting up to 10.000 s for the same device to come "
                   "back",
                   "restart 2/4: the controller went away (the fake controller hung up) while "
                   "waiting for step 4 (action 6 of 10: block 0, index 5); the device came back "
                   "on fake controller"}));
  EXPECT_EQ(r.result.reopens, 1);
  EXPECT_EQ(r.result.restarts, 1);
  EXPECT_EQ(r.result.retries, 0);
  EXPECT_GE(r.result.elapsed, 2s);
  // After the hang-up: probe, GroupStop, barrier, step 1 again.
  ASSERT_GT(r.received.size(), action(5) + 4);
  EXPECT_EQ(r.received[action(5)], (lsc::Frame{0x0f, {}}));
  EXPECT_EQ(r.received[action(5) + 1], (lsc::Frame{0x07, {}}));
}

TEST(UploadRules, AHangUpWithNoRestartsLeftIsNotReopened) {
  FakeScript s;
  s.hangup_at = action(5);
  s.back_after = 2s;
  UploadOptions options;
  options.restarts = 0;
  Upload r;
  r.go(s, options);
  EXPECT_EQ(r.result.status, UploadStatus::HangUp);
  EXPECT_EQ(r.result.reopens, 0);
  EXPECT_TRUE(r.events.lines.empty());
  EXPECT_NE(r.result.message.find("(no restarts left)"), std::string::npos) << r.result.message;
}

}  // namespace
}  // namespace seqc::upload
