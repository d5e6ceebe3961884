// Runs the built seqc binary as a person would (a shell, a working directory, stdin) and
// compares what it prints with golden files; shared by the CLI tests that use the binary.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "tests/golden_update.hpp"

namespace seqc::testing {

namespace fs = std::filesystem;

inline const fs::path kSource = SEQC_SOURCE_DIR;
inline const fs::path kGolden = kSource / "tests/golden";
inline const fs::path kCliGolden = kSource / "tests/cli/golden";

inline std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

struct SeqcRun {
  std::string out;
  std::string err;
  int status = -1;
};

// Runs `seqc args` in `dir` with the shell (args are trusted test strings).
inline SeqcRun seqc(const fs::path& dir, const std::string& args,
                    const std::string& stdin_file = "") {
  static int counter = 0;  // output files are named by pid and counter
  const fs::path tmp = fs::path(SEQC_BINARY_DIR) / "tests/cli/tmp";
  fs::create_directories(tmp);
  const std::string tag = std::to_string(::getpid()) + "-" + std::to_string(counter++);
  const fs::path out = tmp / ("out-" + tag);
  const fs::path err = tmp / ("err-" + tag);
  std::string cmd = "cd '" + dir.string() + "' && '" SEQC_BIN "' " + args + " >'" + out.string() +
                    "' 2>'" + err.string() + "'";
  cmd += " <" + (stdin_file.empty() ? std::string("/dev/null") : "'" + stdin_file + "'");
  const int raw = std::system(cmd.c_str());
  SeqcRun r{slurp(out), slurp(err), WIFEXITED(raw) ? WEXITSTATUS(raw) : -1};
  fs::remove(out);
  fs::remove(err);
  return r;
}

// Compares `actual` with the golden file, or under SEQC_UPDATE_GOLDEN=1 writes it through
// write_golden (which reports every file it changes).
inline void expect_golden(const fs::path& golden, const std::string& actual) {
  if (seqc::testing::updating_goldens()) {
    EXPECT_NE(seqc::testing::write_golden(golden, actual), seqc::testing::GoldenWrite::Failed)
        << golden;
    return;
  }
  ASSERT_TRUE(fs::exists(golden)) << golden << " is missing; run with SEQC_UPDATE_GOLDEN=1";
  EXPECT_EQ(slurp(golden), actual) << "differs from " << golden;
}

}  // namespace seqc::testing
