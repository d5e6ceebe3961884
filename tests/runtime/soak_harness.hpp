// The upload soak's fault model and one run of it, shared by the soak test (ctest, label
// `soak`) and soak_bench (10,000 uploads at x1 and x4). Every upload is a full 1,020-action
// download with GroupRun through the real uploader to the in-process emulator, in emulated
// time; every fault is drawn from seeds, so a run is the same on every machine.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "runtime/emulator/emulator_transport.hpp"
#include "runtime/emulator/xarm_emulator.hpp"
#include "runtime/protocol/group_download.hpp"
#include "runtime/upload/uploader.hpp"

namespace seqc::soak {

using namespace std::chrono_literals;

// Per-frame rates at scale 1 (each multiplied by the scale), and per-upload chances.
inline constexpr double kFrameRate = 0.0005;   // drop, corrupt, late, duplicate, busy
inline constexpr double kResetRate = 0.00002;  // controller reset, per frame
inline constexpr double kHangupChance = 0.02;  // an upload whose port hangs up once

inline std::string fault_model(double scale) {
  char buf[1400];
  const double frame = 100 * kFrameRate * scale;
  std::snprintf(
      buf, sizeof buf,
      "fault model (x%.2f), drawn per upload from its own seed:\n"
      "  per request frame the controller receives:\n"
      "    lost %.4f%%; a framing byte flipped, so it is ignored, %.4f%%;\n"
      "    busy %.4f%%: processed 400 ms longer (700 ms in a quarter of the uploads), frames\n"
      "      arriving meanwhile are dropped;\n"
      "    controller reset %.5f%%: the frame is lost, the download in progress forgotten,\n"
      "      deaf for 300 ms, then answers as after power-on\n"
      "  per frame the controller sends:\n"
      "    a byte flipped %.4f%%; late %.4f%% (by 400 ms, or 700 ms -- beyond the 500 ms reply\n"
      "      margin -- in a quarter of the uploads); sent twice %.4f%%\n"
      "  per upload: the port hangs up at a random frame (1-1030) in %.2f%% of the uploads;\n"
      "    the same device comes back 2 s later\n"
      "  link: half the uploads unpaced, half paced at 115200 baud; reply margin 0.5 s (3 s\n"
      "    for step 1); 4 re-sends per frame, 3 restarts per upload; GroupRun after each\n",
      scale, frame, frame, frame, 100 * kResetRate * scale, frame, frame, frame,
      100 * kHangupChance * scale);
  return buf;
}

inline std::vector<lsc::GroupAction> soak_actions(std::uint64_t seed) {
  emu::SplitMix64 rng(seed);
  std::vector<lsc::GroupAction> actions(1020);
  for (auto& a : actions) {
    a.time_ms = static_cast<std::uint16_t>(20 + rng.next() % 2000);
    for (std::uint8_t s = 1; s <= 6; ++s) {
      a.servos.push_back({s, static_cast<std::uint16_t>(rng.next() % 1001)});
    }
  }
  return actions;
}

// A restart's reason, in one of a few classes for the report.
inline std::string restart_cause(const std::string& reason) {
  if (reason.find("came back") != std::string::npos) return "port hung up and came back";
  if (reason.find("did not acknowledge") != std::string::npos) return "no ack after re-sends";
  if (reason.find("refused") != std::string::npos) {
    return reason.find("taken for the wrong frame") != std::string::npos
               ? "refused twice after a re-send or an extra ack"
               : "refused twice (controller reset?)";
  }
  if (reason.find("while waiting for") != std::string::npos) return "ack of an earlier step taken";
  if (reason.find("before the barrier") != std::string::npos) return "extra ack at a barrier";
  if (reason.find("between frames") != std::string::npos) return "extra ack between frames";
  return "other";
}

// Keeps the last notes of an upload, to show how a failure came about.
class LastNotes final : public upload::UploadObserver {
 public:
  void on_retry(const upload::RetryEvent& e) override {
    add("re-send " + e.what + ": " + e.reason);
  }
  void on_restart(const upload::RestartEvent& e) override {
    add("RESTART: " + e.reason);
    causes.push_back(restart_cause(e.reason));
  }
  void on_note(const std::string& n) override { add(n); }
  void add(std::string n) {
    if (notes.size() == 12) notes.erase(notes.begin());
    notes.push_back(std::move(n));
  }
  std::vector<std::string> notes;
  std::vector<std::string> causes;
};

struct Totals {
  std::size_t uploads = 0, completed = 0, failed = 0;
  std::size_t wrong_success = 0;      // reported success, stored group differs from the plan
  std::size_t run_after_failure = 0;  // GroupRun reached the controller after a failure
  std::size_t with_hangup = 0, with_reset = 0;
  std::size_t retries = 0, restarts = 0, reopens = 0;
  std::map<std::string, std::size_t> failures;  // status: first words of the message -> count
  std::map<std::string, std::size_t> restart_causes;
  std::vector<std::string> first_failures;  // with their last notes (at most 3)

  double completion() const {
    return uploads == 0 ? 0 : static_cast<double>(completed) / static_cast<double>(uploads);
  }
};

// Upload number i of a soak at `scale`, added to `t`.
inline void soak_one(std::size_t i, double scale, Totals& t) {
  emu::SplitMix64 plan_rng(20240611 + i);
  emu::XArmConfig config;
  config.baud = (i % 2 == 0) ? 0 : 115200;
  config.faults.seed = 1000 + i;
  const double rate = kFrameRate * scale;
  config.faults.drop = rate;
  config.faults.corrupt = rate;
  // Corrupted LEN bytes are part of the soak's fault mix; the figures were measured with the
  // inter-byte gap that lets the emulator drop such a frame, so the soak keeps it on.
  config.faults.frame_gap = 20ms;
  config.faults.late_ack = rate;
  config.faults.late_by = (i % 4 == 1) ? 700ms : 400ms;
  config.faults.duplicate_ack = rate;
  config.faults.busy = rate;
  config.faults.busy_for = (i % 4 == 3) ? 700ms : 400ms;
  config.faults.reset = kResetRate * scale;
  const bool hangup = plan_rng.unit() < kHangupChance * scale;
  if (hangup) {
    config.faults.hangup_at = 1 + plan_rng.next() % 1030;
    config.faults.back_after = 2s;
  }

  emu::XArmEmulator emulator(config);
  io::ManualClock clock;
  emu::EmulatorTransport transport(emulator, clock);
  upload::ControllerLink link(transport, clock);
  upload::UploadOptions options;
  options.group = static_cast<std::uint8_t>(i % 8);
  options.run = true;
  LastNotes notes;
  upload::Uploader uploader(link, options, &notes);
  const auto actions = soak_actions(i);
  const auto plan = lsc::plan_group_download(options.group, actions);
  if (!plan.ok()) {
    ++t.failed;
    ++t.failures["bad plan"];
    return;
  }
  const upload::UploadResult r = uploader.upload(*plan);

  ++t.uploads;
  t.retries += static_cast<std::size_t>(r.retries);
  t.restarts += static_cast<std::size_t>(r.restarts);
  t.reopens += static_cast<std::size_t>(r.reopens);
  for (const auto& c : notes.causes) ++t.restart_causes[c];
  if (hangup && emulator.frames_received() >= *config.faults.hangup_at) ++t.with_hangup;
  if (emulator.resets() > 0) ++t.with_reset;
  const auto stored = emulator.stored_group(options.group);
  if (r.ok()) {
    ++t.completed;
    if (!stored || *stored != actions) ++t.wrong_success;
    return;
  }
  ++t.failed;
  for (const emu::ReceivedFrame& f : emulator.received()) {
    if (f.frame && f.frame->cmd == static_cast<std::uint8_t>(lsc::Command::GroupRun)) {
      ++t.run_after_failure;
      break;
    }
  }
  // Grouped by status and cause (the message up to its first parenthesis: which frame differs).
  ++t.failures[std::string(upload::to_string(r.status)) + ": " +
               r.message.substr(0, r.message.find(" ("))];
  if (t.first_failures.size() < 3) {
    std::string s = "upload " + std::to_string(i) + " (baud " + std::to_string(config.baud) +
                    ", faults " + emu::describe_faults(config.faults) + ") failed: " + r.message;
    for (const auto& n : notes.notes) s += "\n    " + n;
    t.first_failures.push_back(s);
  }
}

inline std::string report(const Totals& t, double scale) {
  char buf[600];
  std::snprintf(buf, sizeof buf,
                "soak x%.2f: %zu uploads of 1020 actions: %zu completed (%.3f%%), %zu failed; "
                "%zu reported success with a wrong group; %zu GroupRun after a failed "
                "download; %zu met a hang-up, %zu a controller reset; %zu re-sends, %zu "
                "restarts, %zu reconnects\n",
                scale, t.uploads, t.completed, 100 * t.completion(), t.failed, t.wrong_success,
                t.run_after_failure, t.with_hangup, t.with_reset, t.retries, t.restarts, t.reopens);
  std::string out = buf;
  for (const auto& [what, n] : t.restart_causes) {
    out += "  restarts x" + std::to_string(n) + ": " + what + "\n";
  }
  for (const auto& [what, n] : t.failures) {
    out += "  failure x" + std::to_string(n) + ": " + what + "\n";
  }
  for (const auto& f : t.first_failures) out += "  " + f + "\n";
  return out;
}

}  // namespace seqc::soak
