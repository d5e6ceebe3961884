// soak_bench: the upload soak at its full size. --uploads N (default 10,000) full 1,020-action
// uploads with GroupRun, through the real uploader to the in-process emulator, under the seeded
// fault mix of tests/runtime/soak_harness.hpp, at each --scale (default 1 and 4), in emulated
// time. Prints the fault model, then per scale: uploads completed (target >= 99.9 %), uploads
// that reported success with a wrong stored group (target 0; the emulator's stored group is
// compared with the plan), GroupRun frames the controller received after a failed download
// (target 0), the recovery work done, per kind of fault how often it happened and which
// recoveries handled it (target: every kind happened), every failure's message, and the wall
// time the run took.
//
// Usage: soak_bench [--uploads N] [--scale S]...
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "tests/runtime/soak_harness.hpp"

int main(int argc, char** argv) {
  std::size_t uploads = 10000;
  std::vector<double> scales;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--uploads") == 0 && i + 1 < argc) {
      uploads = std::strtoull(argv[++i], nullptr, 10);
    } else if (std::strcmp(argv[i], "--scale") == 0 && i + 1 < argc) {
      scales.push_back(std::strtod(argv[++i], nullptr));
    } else {
      std::fprintf(stderr, "usage: soak_bench [--uploads N] [--scale S]...\n");
      return 2;
    }
  }
  if (scales.empty()) scales = {1.0, 4.0};
  int status = 0;
  for (double scale : scales) {
    const auto start = std::chrono::steady_clock::now();
    seqc::soak::Totals t;
    for (std::size_t i = 0; i < uploads; ++i) seqc::soak::soak_one(i, scale, t);
    seqc::soak::soak_isolated(uploads, std::max<std::size_t>(uploads / 100, 5), scale, t);
    const double secs =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("%s%s", seqc::soak::fault_model(scale).c_str(),
                seqc::soak::report(t, scale).c_str());
    const auto never = t.faults_never_seen();
    const bool met = t.completion() >= 0.999 && t.wrong_success == 0 && t.run_after_failure == 0 &&
                     never.empty() && t.tally_mismatches == 0;
    std::printf(
        "targets (>= 99.9%% complete, 0 wrong successes no flipped byte explains, 0 GroupRun "
        "after failure, every kind of fault happened): %s\n",
        met ? "met" : "NOT met");
    for (const std::string& kind : never) std::printf("  never happened: %s\n", kind.c_str());
    std::printf("wall time: %.1f s (%.2f ms per upload)\n\n", secs,
                1000 * secs / static_cast<double>(uploads));
    if (t.wrong_success != 0 || t.run_after_failure != 0 || !never.empty() ||
        t.tally_mismatches != 0) {
      status = 1;
    }
  }
  return status;
}
