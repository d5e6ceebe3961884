// The language features a person meets through `seqc check` and `seqc compile`: servo groups, the
// warning for a section never performed, a vertical ease under --strict, and the car's pan and
// tilt in separate tracks. Each runs the real binary on a file written here; the expected
// statuses are docs/cli.md's (0 ok, 1 invalid input) and the messages and frames are worked out
// by hand from docs/language.md and docs/protocol/raspblock.md.
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "tests/cli/seqc_run.hpp"

namespace seqc::testing {
namespace {

// A scratch folder of its own for each test, holding `name` with `text`.
fs::path write_file(const std::string& name, const std::string& text) {
  const fs::path dir = fs::path(SEQC_BINARY_DIR) / "tests/cli/tmp/language-features" /
                       ::testing::UnitTest::GetInstance()->current_test_info()->name();
  fs::create_directories(dir);
  std::ofstream(dir / name, std::ios::binary) << text;
  return dir;
}

TEST(LanguageFeaturesCli, AGroupBreakingALimitNamesTheMember) {
  const fs::path dir = write_file("legs.yaml", R"(robot:
  profile: bus
  servos: {lf_coxa: 1, lm_coxa: 2, lr_coxa: 3}
groups:
  left: [lf_coxa, lm_coxa, lr_coxa]
sequence:
  - move: {left: 500}
    time: 1s
  - move: {lm_coxa: 950}
    time: 1s
  - move: {left: +100}
    time: 1s
)");
  const SeqcRun r = seqc(dir, "check legs.yaml");
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_NE(r.err.find("legs.yaml:11:18: error: 'lm_coxa' would move to 1050 (950 +100), above "
                       "its max 1000"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("legs.yaml:5:19: note: 'lm_coxa' moves through group 'left', which lists "
                       "it here"),
            std::string::npos)
      << r.err;
}

TEST(LanguageFeaturesCli, ASectionNeverPerformedIsAWarning) {
  const fs::path dir = write_file("spare.yaml", R"(robot: xarm
sections:
  spare: [{move: {base: +10}, time: 1s}]
sequence:
  - move: home
    time: 2s
)");
  for (const char* command : {"check", "compile"}) {
    const SeqcRun r = seqc(dir, std::string(command) + " spare.yaml");
    EXPECT_EQ(r.status, 0) << command << ": " << r.err;
    EXPECT_NE(r.err.find("spare.yaml:3:3: warning: section 'spare' is defined but never performed"),
              std::string::npos)
        << command << ": " << r.err;
  }
}

TEST(LanguageFeaturesCli, CircInChecksCleanUnderStrictWhenItsToleranceAllows) {
  // 100 units of circ-in in 2 s at tolerance 5 needs (100^2 - 5^2) / (2 x 5 x 2 s) = 498.75/s.
  auto file = [](const char* max_speed) {
    return std::string("robot:\n  profile: xarm\n  servos:\n    base: {max_speed: ") + max_speed +
           "}\nsequence:\n  - move: {base: 450}\n    time: 2s\n  - move: {base: 550}\n"
           "    time: 2s\n    ease: circ-in\n    tolerance: 5\n";
  };
  fs::path dir = write_file("circ.yaml", file("500/s"));
  SeqcRun r = seqc(dir, "check --strict circ.yaml");
  EXPECT_EQ(r.status, 0) << r.err;
  dir = write_file("circ.yaml", file("400/s"));
  r = seqc(dir, "check --strict circ.yaml");
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_NE(r.err.find("circ.yaml:8:5: error: 100 in 2000ms needs at least 498.75/s on this "
                       "circ-in curve within a tolerance of 5, above base's 400/s [--strict]"),
            std::string::npos)
      << r.err;
}

TEST(LanguageFeaturesCli, PanAndTiltInSeparateTracksCompileToOnePacketAnInstant) {
  const fs::path dir = write_file("camera.yaml", R"(robot: raspblock
sequence:
  - together:
      look:
        - move: {pan: 2000}
          time: 100ms
      nod:
        - move: {tilt: 1000}
          time: 100ms
)");
  const SeqcRun r = seqc(dir, "compile camera.yaml");
  EXPECT_EQ(r.status, 0) << r.err;
  // FF FE 02 04, pan 2000 = 07 d0, tilt 1000 = 03 e8, CHK = 02 + 04 + 07 + d0 + 03 + e8 = 0x1c8;
  // then the stop, rocker 0,0,0 (FF FE 03 08 01 00 00 00 00 00 00 01 0D).
  EXPECT_EQ(r.out,
            "     0 ms  ff fe 02 04 07 d0 03 e8 c8\n"
            "   100 ms  ff fe 03 08 01 00 00 00 00 00 00 01 0d\n");
}

}  // namespace
}  // namespace seqc::testing
