// Golden `--help` of the servo controller commands: what a person reads is reviewed once and
// then pinned. SEQC_UPDATE_GOLDEN=1 rewrites the files instead (review every change by eye).
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "tests/cli/device_test_util.hpp"
#include "tests/golden_update.hpp"

namespace seqc::cli::test {
namespace {

const std::string kGoldenDir = std::string(SEQC_SOURCE_DIR) + "/tests/golden/device-help/";

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

class DeviceHelp : public ::testing::TestWithParam<std::vector<std::string>> {};

TEST_P(DeviceHelp, MatchesGolden) {
  std::vector<std::string> args = GetParam();
  std::string name;
  for (const std::string& a : args) name += (name.empty() ? "" : "-") + a;
  args.push_back("--help");
  DeviceHarness h;
  RunResult r = h.run(args);
  EXPECT_EQ(r.code, 0);
  EXPECT_EQ(r.err, "");
  const std::string path = kGoldenDir + name + ".txt";
  if (seqc::testing::updating_goldens()) {
    EXPECT_NE(seqc::testing::write_golden(path, r.out), seqc::testing::GoldenWrite::Failed) << path;
    return;
  }
  EXPECT_EQ(r.out, read_file(path)) << path;
  EXPECT_EQ(h.received(), "");
}

INSTANTIATE_TEST_SUITE_P(
    Commands, DeviceHelp,
    ::testing::Values(
        std::vector<std::string>{"group"}, std::vector<std::string>{"group", "run"},
        std::vector<std::string>{"group", "stop"}, std::vector<std::string>{"group", "erase"},
        std::vector<std::string>{"group", "speed"}, std::vector<std::string>{"battery"},
        std::vector<std::string>{"servo"}, std::vector<std::string>{"servo", "read"},
        std::vector<std::string>{"servo", "off"}, std::vector<std::string>{"servo", "move"},
        std::vector<std::string>{"servo", "mode"}, std::vector<std::string>{"offset"},
        std::vector<std::string>{"offset", "read"}, std::vector<std::string>{"offset", "adjust"},
        std::vector<std::string>{"offset", "write"}, std::vector<std::string>{"bus-info"},
        std::vector<std::string>{"bus-info", "read"},
        std::vector<std::string>{"bus-info", "write"}),
    [](const ::testing::TestParamInfo<std::vector<std::string>>& param_info) {
      std::string name;
      for (const std::string& a : param_info.param) {
        for (char c : a) name += (c == '-') ? '_' : c;
        name += '_';
      }
      name.pop_back();
      return name;
    });

}  // namespace
}  // namespace seqc::cli::test
