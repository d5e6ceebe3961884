// Soak: full 1,020-action uploads (with GroupRun) against the in-process emulator under the
// seeded fault mix of soak_harness.hpp, in emulated time. Checked: no upload reports success
// while the stored group differs from the plan, except where the controller stored an action
// whose time, ids or positions a flipped byte changed on the wire (no checksum, no read-back:
// the report counts them, and every other flipped byte was caught); no GroupRun reaches the
// controller after a failed download; at least 99.9 % of the uploads complete (hang-ups included:
// the device comes back); every kind of fault injected happened at least once (the per-kind table
// of faults and the recoveries that handled them is printed). SEQC_SOAK_UPLOADS sets the number of
// uploads (default 1,000), SEQC_SOAK_SCALE the fault scale (default 1); tests/bench/soak_bench runs
// 10,000 at x1 and x4.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "tests/runtime/soak_harness.hpp"

namespace seqc::soak {
namespace {

std::size_t env_or(const char* name, std::size_t fallback) {
  const char* v = std::getenv(name);
  return v != nullptr && *v != '\0' ? std::strtoull(v, nullptr, 10) : fallback;
}
double env_or(const char* name, double fallback) {
  const char* v = std::getenv(name);
  return v != nullptr && *v != '\0' ? std::strtod(v, nullptr) : fallback;
}

// Uploads per fault injected alone, after the mixed soak (the per-fault recovery table).
constexpr std::size_t kIsolatedPerKnob = 20;

TEST(UploadSoak, MixedFaultsNeverReportAWrongGroupAndFinish) {
  const std::size_t uploads = env_or("SEQC_SOAK_UPLOADS", std::size_t{1000});
  const double scale = env_or("SEQC_SOAK_SCALE", 1.0);
  Totals t;
  for (std::size_t i = 0; i < uploads; ++i) soak_one(i, scale, t);
  soak_isolated(uploads, kIsolatedPerKnob, scale, t);
  std::printf("%s%s", fault_model(scale).c_str(), report(t, scale).c_str());
  EXPECT_EQ(t.uploads, uploads + kIsolatedPerKnob * fault_knobs().size());
  EXPECT_EQ(t.wrong_success, 0u);
  // Flips landed both where a refusal or silence reveals them and where nothing can; only the
  // latter ever left a wrong group behind a reported success.
  EXPECT_GT(t.flips["action time, ids, positions"].flips, 0u);
  EXPECT_GT(t.flips["command byte"].flips + t.flips["action block or index"].flips, 0u);
  for (const auto& [place, f] : t.flips) {
    if (place != "action time, ids, positions") {
      EXPECT_EQ(f.stored_wrong, 0u) << place;
    }
  }
  EXPECT_LE(t.undetectable_flip, t.flips["action time, ids, positions"].flips);
  EXPECT_EQ(t.run_after_failure, 0u);
  EXPECT_GT(t.with_hangup, 0u);  // the mix did exercise reconnecting
  EXPECT_GE(t.completion(), 0.999);
  // Every kind of fault the soak injects happened, so none of the checks above passed for not
  // being exercised; and every upload's faults were accounted for.
  EXPECT_EQ(t.faults_never_seen(), std::vector<std::string>{});
  EXPECT_EQ(t.tally_mismatches, 0u);
}

}  // namespace
}  // namespace seqc::soak
