// The uploader's recovery against the emulated controller, in emulated time: a controller reset
// mid-download, a port that hangs up and comes back (or does not), and the state an interrupted
// upload leaves behind. Frames the controller must receive are written out by hand from
// docs/protocol/servo-controller.md.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <functional>
#include <optional>

#include "runtime/emulator/emulator_transport.hpp"
#include "runtime/emulator/xarm_emulator.hpp"
#include "protocol/lsc/group_download.hpp"
#include "runtime/upload/uploader.hpp"

namespace seqc::upload {
namespace {

using namespace std::chrono_literals;

// Request numbers as the controller counts them for 1,020 actions (4 blocks): 1 probe,
// 2 GroupStop, 3 barrier, 4 step 1, 5-8 step 2, 9 step 3, then action k (0-based) is 10 + k.
constexpr std::size_t action_frame(std::size_t k) { return 10 + k; }

std::vector<lsc::GroupAction> actions_1020() {
  std::vector<lsc::GroupAction> actions(1020);
  for (std::size_t i = 0; i < actions.size(); ++i) {
    actions[i].time_ms = static_cast<std::uint16_t>(100 + i % 300);
    for (std::uint8_t s = 1; s <= 6; ++s) {
      actions[i].servos.push_back({s, static_cast<std::uint16_t>((i * 13 + s * 97) % 1001)});
    }
  }
  return actions;
}

class Hooks final : public UploadObserver {
 public:
  std::function<void(const UploadProgress&)> progress;
  std::vector<RestartEvent> restarts;
  void on_progress(const UploadProgress& p) override {
    if (progress) progress(p);
  }
  void on_restart(const RestartEvent& e) override { restarts.push_back(e); }
};

// Forwards to the emulator's transport; sets the interrupt flag once a frame of command
// `interrupt_after` has been written (Ctrl-C right after it went out).
class InterruptAfter final : public io::Transport {
 public:
  InterruptAfter(io::Transport& inner, std::optional<std::uint8_t> cmd, std::atomic<bool>& flag)
      : inner_(inner), cmd_(cmd), flag_(flag) {}
  Status write(ByteView bytes) override {
    Status st = inner_.write(bytes);
    if (cmd_ && bytes.size() > 3 && bytes[3] == *cmd_) flag_ = true;
    return st;
  }
  io::ReadResult read(std::span<std::uint8_t> buffer, io::TimePoint deadline) override {
    return inner_.read(buffer, deadline);
  }
  void discard_input() override { inner_.discard_input(); }
  std::string describe() const override { return inner_.describe(); }
  double seconds_per_byte() const override { return inner_.seconds_per_byte(); }
  bool reopen(io::TimePoint deadline) override { return inner_.reopen(deadline); }

 private:
  io::Transport& inner_;
  std::optional<std::uint8_t> cmd_;
  std::atomic<bool>& flag_;
};

struct Scenario {
  emu::XArmConfig config;
  UploadOptions options;
  io::ManualClock clock;
  std::atomic<bool> interrupted{false};
  Hooks hooks;
  std::vector<lsc::GroupAction> actions = actions_1020();
  std::optional<std::uint8_t> interrupt_after;

  // Runs the upload; the emulator is left for the test to inspect.
  UploadResult go(emu::XArmEmulator& emulator) {
    emu::EmulatorTransport emulated(emulator, clock);
    InterruptAfter transport(emulated, interrupt_after, interrupted);
    ControllerLink link(transport, clock, &interrupted);
    Uploader uploader(link, options, &hooks);
    const auto plan = lsc::plan_group_download(options.group, actions);
    EXPECT_TRUE(plan.ok());
    return uploader.upload(*plan);
  }
};

bool received_group_run(const emu::XArmEmulator& e) {
  for (const auto& f : e.received()) {
    if (f.frame && f.frame->cmd == 0x06) return true;
  }
  return false;
}

TEST(UploadRecovery, ControllerResetMidDownloadRestartsFromStep1AndStores) {
  Scenario r;
  r.config.faults.reset_at = action_frame(300);
  r.options.run = true;
  emu::XArmEmulator emulator(r.config);
  const UploadResult res = r.go(emulator);
  EXPECT_EQ(emulator.resets(), 1u);
  ASSERT_EQ(res.status, UploadStatus::Completed) << res.message;
  EXPECT_EQ(res.restarts, 1);
  ASSERT_EQ(r.hooks.restarts.size(), 1u);
  EXPECT_NE(r.hooks.restarts[0].reason.find("it may have restarted (a power dip"),
            std::string::npos)
      << r.hooks.restarts[0].reason;
  ASSERT_TRUE(emulator.stored_group(0).has_value());
  EXPECT_EQ(*emulator.stored_group(0), r.actions);
  EXPECT_TRUE(received_group_run(emulator));
}

TEST(UploadRecovery, ControllerResetWithoutRestartsLeftFailsClearlyAndNeverRuns) {
  Scenario r;
  r.config.faults.reset_at = action_frame(300);
  r.options.run = true;
  r.options.restarts = 0;
  emu::XArmEmulator emulator(r.config);
  const UploadResult res = r.go(emulator);
  EXPECT_EQ(res.status, UploadStatus::Refused);
  EXPECT_NE(res.message.find("action 301 of 1020"), std::string::npos) << res.message;
  EXPECT_NE(res.message.find("it may have restarted"), std::string::npos) << res.message;
  EXPECT_EQ(res.group_state, GroupState::Empty);
  EXPECT_FALSE(emulator.stored_group(0).has_value());
  EXPECT_FALSE(received_group_run(emulator));
}

TEST(UploadRecovery, PortThatHangsUpAndComesBackIsReopenedAndTheUploadFinishes) {
  Scenario r;
  r.config.baud = 115200;
  r.config.faults.hangup_at = action_frame(500);
  r.config.faults.back_after = 2s;
  emu::XArmEmulator emulator(r.config);
  const UploadResult res = r.go(emulator);
  ASSERT_EQ(res.status, UploadStatus::Completed) << res.message;
  EXPECT_EQ(res.reopens, 1);
  EXPECT_EQ(res.restarts, 1);
  ASSERT_EQ(r.hooks.restarts.size(), 1u);
  EXPECT_NE(r.hooks.restarts[0].reason.find("the device came back on emu:xarm"), std::string::npos)
      << r.hooks.restarts[0].reason;
  EXPECT_GE(res.elapsed, 2s);
  EXPECT_EQ(*emulator.stored_group(0), r.actions);
}

TEST(UploadRecovery, PortThatStaysAwayEndsTheUploadAfterTheWait) {
  Scenario r;
  r.config.faults.hangup_at = action_frame(500);
  r.options.reopen_wait = 5s;
  emu::XArmEmulator emulator(r.config);
  const UploadResult res = r.go(emulator);
  EXPECT_EQ(res.status, UploadStatus::HangUp);
  EXPECT_NE(res.message.find("it did not come back within 5.000 s"), std::string::npos)
      << res.message;
  EXPECT_EQ(res.group_state, GroupState::Empty);
  EXPECT_EQ(res.reopens, 0);
}

TEST(UploadRecovery, InterruptAfterStep5BeforeItIsConfirmedErasesTheGroup) {
  Scenario r;
  r.options.group = 3;
  r.options.run = true;
  r.hooks.progress = [&](const UploadProgress& p) {
    if (p.frames_total > 0 && p.frames_done == p.frames_total) r.interrupted = true;
  };
  emu::XArmEmulator emulator(r.config);
  const UploadResult res = r.go(emulator);
  EXPECT_EQ(res.status, UploadStatus::Interrupted);
  EXPECT_TRUE(res.erase_sent);
  EXPECT_FALSE(res.stop_sent);  // the upload had stopped any group and never ran one
  EXPECT_EQ(res.group_state, GroupState::Empty);
  // The last frame the controller received: GroupErase of group 3.
  ASSERT_FALSE(emulator.received().empty());
  EXPECT_EQ(emulator.received().back().raw, (Bytes{0x55, 0x55, 0x03, 0x08, 0x03}));
  emulator.advance_to(emulator.now() + 1s);
  EXPECT_FALSE(emulator.stored_group(3).has_value());
  EXPECT_FALSE(received_group_run(emulator));
}

TEST(UploadRecovery, InterruptBeforeTheGroupWasStoppedSendsGroupStop) {
  Scenario r;
  r.interrupted = true;  // Ctrl-C before the first frame
  emu::XArmEmulator emulator(r.config);
  const UploadResult res = r.go(emulator);
  EXPECT_EQ(res.status, UploadStatus::Interrupted);
  EXPECT_TRUE(res.stop_sent);
  EXPECT_FALSE(res.erase_sent);
  EXPECT_EQ(res.group_state, GroupState::Unchanged);
  EXPECT_EQ(emulator.received_bytes(), (Bytes{0x55, 0x55, 0x02, 0x07}));
}

TEST(UploadRecovery, InterruptMidDownloadLeavesTheGroupEmptyAndSendsNothingMore) {
  Scenario r;
  r.hooks.progress = [&](const UploadProgress& p) {
    if (p.actions_done == 400) r.interrupted = true;
  };
  emu::XArmEmulator emulator(r.config);
  const UploadResult res = r.go(emulator);
  EXPECT_EQ(res.status, UploadStatus::Interrupted);
  EXPECT_FALSE(res.stop_sent);
  EXPECT_FALSE(res.erase_sent);
  EXPECT_EQ(res.group_state, GroupState::Empty);
  EXPECT_EQ(res.actions_acknowledged, 400u);
  EXPECT_EQ(emulator.frames_received(), action_frame(400) - 1);
  EXPECT_FALSE(emulator.stored_group(0).has_value());
}

TEST(UploadRecovery, InterruptAfterGroupRunStopsTheGroupItStarted) {
  Scenario r;
  r.options.run = true;
  r.options.run_times = 0;   // loop until stopped
  r.interrupt_after = 0x06;  // Ctrl-C just after GroupRun went out
  emu::XArmEmulator emulator(r.config);
  const UploadResult res = r.go(emulator);
  EXPECT_EQ(res.status, UploadStatus::Interrupted);
  EXPECT_EQ(res.message, "interrupted after starting group 0");
  EXPECT_TRUE(res.run_sent);
  EXPECT_TRUE(res.stop_sent);
  EXPECT_EQ(res.group_state, GroupState::Stored);
  EXPECT_EQ(*emulator.stored_group(0), r.actions);
  EXPECT_EQ(emulator.received().back().raw, (Bytes{0x55, 0x55, 0x02, 0x07}));
  emulator.advance_to(emulator.now() + 5s);
  EXPECT_FALSE(emulator.playing_group().has_value());
}

}  // namespace
}  // namespace seqc::upload
