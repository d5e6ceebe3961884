// `seqc compile` of a dance in triplets with a 3/4 -> 6/8 change, through the real binary: the
// compiled keyframes start where a musician counts them. At 90 bpm a quarter is 2000/3 ms and a
// 3/4 bar 2000 ms; 6/8 keeps the eighth (1000/3 ms), so its bar is 2000 ms too.
#include <gtest/gtest.h>

#include <regex>
#include <string>
#include <vector>

#include "tests/cli/seqc_run.hpp"

namespace seqc::testing {
namespace {

constexpr const char* kTriplets = R"(robot: xarm
tempo: 90
meter: 3/4
sequence:
  - move: {base: 600}
    time: 1/3b
  - move: {base: 650}
    time: 1/3b
  - move: {base: 600}
    time: 1/3b
  - move: {base: 700}
    time: 2b
  - move: {base: 520}
    time: 1bar
  - meter: 6/8
  - move: {base: 600}
    time: 1bar
  - move: {base: 620}
    at: bar 4
    time: 1/6bar
  - tempo: dotted quarter = 60
  - move: {base: 640}
    time: 3b
)";

std::vector<long> json_numbers(const std::string& json, const std::string& key) {
  std::vector<long> out;
  const std::regex re("\"" + key + "\": ([0-9]+)");
  for (auto it = std::sregex_iterator(json.begin(), json.end(), re); it != std::sregex_iterator();
       ++it) {
    out.push_back(std::stol((*it)[1]));
  }
  return out;
}

TEST(NoteValuesCli, TripletsAndASixEightBarStartOnTheirBeats) {
  const fs::path dir = fs::path(SEQC_BINARY_DIR) / "tests/cli/tmp/note-values";
  fs::create_directories(dir);
  { std::ofstream(dir / "triplets.yaml") << kTriplets; }
  const SeqcRun r = seqc(dir, "compile --emit json triplets.yaml");
  ASSERT_EQ(r.status, 0) << r.err;
  // Three thirds of a 2000/3 ms beat: 0, 222.2, 444.4 (rounded once each), ending on beat 2 at
  // 666.7; two beats to 2000 (bar 2); a bar to 4000 (bar 3, where 6/8 starts); a 6/8 bar to
  // 6000 = bar 4; a sixth of it (1000/3 ms) to 6333.3; a dotted quarter at 60 keeps the eighth,
  // so three eighths last 1000 ms.
  EXPECT_EQ(json_numbers(r.out, "start_ms"),
            (std::vector<long>{0, 222, 444, 667, 2000, 4000, 6000, 6333}));
  EXPECT_EQ(json_numbers(r.out, "time_ms"),
            (std::vector<long>{222, 222, 223, 1333, 2000, 2000, 333, 1000}));
  EXPECT_EQ(json_numbers(r.out, "duration_ms"), (std::vector<long>{7333}));
}

}  // namespace
}  // namespace seqc::testing
