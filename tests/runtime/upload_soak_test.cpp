// Soak: many full 1,020-action uploads against the in-process emulator with mixed seeded
// faults, in emulated time. Counts are printed. Requirements checked:
//   - no upload reports success while the emulator's stored group differs from the plan;
//   - at least 99.9 % of the uploads without a hang-up fault complete.
// SEQC_SOAK_UPLOADS sets the number of uploads (default 1,000); SEQC_SOAK_SCALE multiplies
// every fault rate (default 1).
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>

#include "runtime/emulator/emulator_transport.hpp"
#include "runtime/emulator/xarm_emulator.hpp"
#include "runtime/protocol/group_download.hpp"
#include "runtime/upload/uploader.hpp"

namespace seqc::upload {
namespace {

using namespace std::chrono_literals;

std::size_t env_or(const char* name, std::size_t fallback) {
  const char* v = std::getenv(name);
  return v != nullptr && *v != '\0' ? std::strtoull(v, nullptr, 10) : fallback;
}
double env_or(const char* name, double fallback) {
  const char* v = std::getenv(name);
  return v != nullptr && *v != '\0' ? std::strtod(v, nullptr) : fallback;
}

std::vector<lsc::GroupAction> soak_actions(std::uint64_t seed) {
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

// Keeps the last notes of an upload, to show how a failure came about.
class LastNotes final : public UploadObserver {
 public:
  void on_retry(const RetryEvent& e) override { add("re-send " + e.what + ": " + e.reason); }
  void on_note(const std::string& n) override { add(n); }
  void add(std::string n) {
    if (notes.size() == 12) notes.erase(notes.begin());
    notes.push_back(std::move(n));
  }
  std::vector<std::string> notes;
};

TEST(UploadSoak, MixedFaultsNeverReportAWrongGroup) {
  const std::size_t uploads = env_or("SEQC_SOAK_UPLOADS", std::size_t{1000});
  const double scale = env_or("SEQC_SOAK_SCALE", 1.0);

  std::size_t completed = 0, wrong_success = 0, hangup_failed = 0;
  std::size_t hangup_completed = 0, other_failed = 0, retries = 0, restarts = 0;
  std::map<std::string, std::size_t> failures;
  emu::SplitMix64 plan_rng(20240611);

  for (std::size_t i = 0; i < uploads; ++i) {
    emu::XArmConfig config;
    config.baud = (i % 2 == 0) ? 0 : 115200;  // half unpaced, half on a paced wire
    config.faults.seed = 1000 + i;
    config.faults.drop = 0.0005 * scale;
    config.faults.corrupt = 0.0005 * scale;
    config.faults.late_ack = 0.0005 * scale;
    config.faults.late_by = (i % 4 == 1) ? 700ms : 400ms;  // a quarter beyond the margin
    config.faults.duplicate_ack = 0.0005 * scale;
    const bool hangup = plan_rng.unit() < 0.02;
    if (hangup) config.faults.hangup_at = 1 + plan_rng.next() % 1030;

    emu::XArmEmulator emulator(config);
    io::ManualClock clock;
    emu::EmulatorTransport transport(emulator, clock);
    ControllerLink link(transport, clock);
    UploadOptions options;
    options.group = static_cast<std::uint8_t>(i % 8);
    LastNotes notes;
    Uploader uploader(link, options, &notes);
    const auto actions = soak_actions(i);
    const auto plan = lsc::plan_group_download(options.group, actions);
    ASSERT_TRUE(plan.ok());
    const UploadResult r = uploader.upload(*plan);
    retries += static_cast<std::size_t>(r.retries);
    restarts += static_cast<std::size_t>(r.restarts);

    const auto stored = emulator.stored_group(options.group);
    if (r.ok()) {
      ++completed;
      if (hangup) ++hangup_completed;
      if (!stored || *stored != actions) {
        ++wrong_success;
        ADD_FAILURE() << "upload " << i << " reported success but the group differs";
      }
    } else if (hangup) {
      ++hangup_failed;
    } else {
      if (other_failed < 3) {
        std::printf("upload %zu (baud %u, faults %s) failed: %s\n", i, config.baud,
                    emu::describe_faults(config.faults).c_str(), r.message.c_str());
        for (const auto& n : notes.notes) std::printf("    %s\n", n.c_str());
      }
      ++other_failed;
      ++failures[std::string(to_string(r.status)) + ": " + r.message];
    }
  }

  const std::size_t without_hangup = uploads - hangup_failed - hangup_completed;
  std::printf(
      "soak: %zu uploads of 1020 actions (fault rates x%.2f): %zu completed, %zu with a hang-up "
      "fault (%zu failed, %zu completed before it), %zu other failures, %zu reported success "
      "with a wrong group; %zu re-sends, %zu restarts\n",
      uploads, scale, completed, hangup_failed + hangup_completed, hangup_failed, hangup_completed,
      other_failed, wrong_success, retries, restarts);
  for (const auto& [what, n] : failures) std::printf("  failure x%zu: %s\n", n, what.c_str());

  EXPECT_EQ(wrong_success, 0u);
  ASSERT_GT(without_hangup, 0u);
  const double rate =
      static_cast<double>(without_hangup - other_failed) / static_cast<double>(without_hangup);
  std::printf("soak: completion without hang-up faults %.4f%%\n", rate * 100);
  EXPECT_GE(rate, 0.999);
}

}  // namespace
}  // namespace seqc::upload
