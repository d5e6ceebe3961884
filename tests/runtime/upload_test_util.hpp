// Shared by the uploader's tests against the scripted controller (upload_fake_controller.hpp):
// the plan, the request numbers the controller counts, one upload run in emulated time, and the
// property every test checks.
#pragma once

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "protocol/lsc/group_download.hpp"
#include "runtime/upload/uploader.hpp"
#include "tests/runtime/upload_fake_controller.hpp"

namespace seqc::upload {

using testing::FakeController;
using testing::FakeScript;

inline std::vector<lsc::GroupAction> make_actions(std::size_t n, std::uint8_t servos = 6) {
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

inline Outcome run_upload(FakeScript script, std::size_t n = 1020, UploadOptions options = {},
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

inline lsc::Frame frame_of(const lsc::Request& r) { return lsc::encode(r).value(); }

// The one property every test checks: success means the controller holds exactly the plan.
inline void expect_consistent(const Outcome& o) {
  if (o.result.ok()) {
    ASSERT_TRUE(o.stored.has_value());
    EXPECT_EQ(*o.stored, o.actions);
    EXPECT_EQ(o.result.group_state, GroupState::Stored);
    EXPECT_EQ(o.result.actions_acknowledged, o.actions.size());
  }
}

inline const Numbers k1020{4, 1020};

// The upload completed after exactly `restarts` restarts and stored the plan.
inline void expect_completed_after(const Outcome& o, int restarts) {
  expect_consistent(o);
  EXPECT_EQ(o.result.status, UploadStatus::Completed) << o.result.message;
  EXPECT_EQ(o.result.restarts, restarts);
  ASSERT_TRUE(o.stored.has_value());
  EXPECT_EQ(*o.stored, o.actions);
}

// Every event an uploader reports but progress, in order, one line each, for tests that assert
// the path an upload took (which re-sends, restarts and notes), not only where it ended.
class Events final : public UploadObserver {
 public:
  void on_progress(const UploadProgress& p) override {
    if (progress) progress(p);
  }
  void on_retry(const RetryEvent& e) override {
    lines.push_back("retry " + e.what + " " + std::to_string(e.attempt) + "/" +
                    std::to_string(e.max_attempts) + ": " + e.reason);
  }
  void on_restart(const RestartEvent& e) override {
    lines.push_back("restart " + std::to_string(e.attempt) + "/" + std::to_string(e.max_attempts) +
                    ": " + e.reason);
  }
  void on_note(const std::string& n) override { lines.push_back("note: " + n); }

  std::function<void(const UploadProgress&)> progress;
  std::vector<std::string> lines;
};

}  // namespace seqc::upload
