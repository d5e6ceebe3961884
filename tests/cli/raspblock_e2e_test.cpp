// End to end with the real binary: `seqc emulate raspblock --record timeline.csv` serves the
// board on a pseudo-terminal, `seqc play examples/car-dance.yaml --port <pty>` plays to it in
// real time, and the recorded timeline must equal the one the compiled stream implies (same
// changes in the same order). How closely the times are kept depends on the machine's load;
// tests/bench/play_bench measures that.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "compiler/compile.hpp"
#include "compiler/targets/raspblock/raspblock_stream.hpp"
#include "runtime/emulator/raspblock_emulator.hpp"
#include "runtime/io/disk.hpp"

namespace {

namespace fs = std::filesystem;

struct Row {
  double t = 0;
  std::string change;  // "field,previous,value"
};

std::vector<Row> parse_csv(const std::string& text) {
  std::vector<Row> rows;
  std::istringstream in(text);
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    const auto comma = line.find(',');
    rows.push_back({std::stod(line.substr(0, comma)), line.substr(comma + 1)});
  }
  return rows;
}

// How many state changes the emulator has printed to its log so far ("<time> s  <field> ...").
std::size_t changes_logged(const fs::path& log) {
  std::ifstream in(log);
  std::size_t n = 0;
  for (std::string line; std::getline(in, line);) {
    if (line.find(" s  ") != std::string::npos) ++n;
  }
  return n;
}

TEST(RaspblockEndToEnd, EmulatorRecordsTheCompiledCarDance) {
  // What the compiled stream means for the board, fed in at the stream's own times.
  seqc::io::DiskFileReader files;
  auto compiled = seqc::compiler::compile_file(
      std::string(SEQC_SOURCE_DIR) + "/examples/car-dance.yaml", files);
  ASSERT_NE(compiled.raspblock_program(), nullptr);
  auto frames = seqc::compiler::plan_stream(*compiled.raspblock_program());
  ASSERT_TRUE(frames.ok());
  seqc::emu::RaspblockEmulator expected;
  for (const auto& f : *frames) expected.receive(f.bytes, std::chrono::milliseconds(f.at_ms));
  const std::vector<Row> want = parse_csv(seqc::emu::timeline_csv(expected.timeline()));

  const fs::path tmp =
      fs::path(SEQC_BINARY_DIR) / "tests/cli/tmp" / ("e2e-" + std::to_string(::getpid()));
  fs::create_directories(tmp);
  const fs::path csv = tmp / "timeline.csv";
  const fs::path emu_err = tmp / "emulate.stderr";

  // The emulator, with its stdout (the pty path) on a pipe.
  int pipefd[2];
  ASSERT_EQ(::pipe(pipefd), 0);
  const pid_t emu = ::fork();
  ASSERT_GE(emu, 0);
  if (emu == 0) {
    ::dup2(pipefd[1], STDOUT_FILENO);
    std::freopen(emu_err.c_str(), "w", stderr);
    ::close(pipefd[0]);
    ::execl(SEQC_BIN, "seqc", "emulate", "raspblock", "--record", csv.c_str(),
            static_cast<char*>(nullptr));
    std::_Exit(127);
  }
  ::close(pipefd[1]);
  std::string pty;
  char c = 0;
  while (::read(pipefd[0], &c, 1) == 1 && c != '\n') pty += c;
  ASSERT_FALSE(pty.empty()) << "seqc emulate printed no terminal";

  const std::string play = "cd '" + std::string(SEQC_SOURCE_DIR) +
                           "' && '" SEQC_BIN "' play examples/car-dance.yaml --port " + pty +
                           " 2>'" + (tmp / "play.stderr").string() + "'";
  const int raw = std::system(play.c_str());
  // Stop the emulator once it has logged every change (a give-up only guards against a lost
  // packet, which the comparison below then reports).
  for (int i = 0; i < 2000 && changes_logged(emu_err) < want.size(); ++i) ::usleep(5000);
  ::kill(emu, SIGINT);
  int status = 0;
  ::waitpid(emu, &status, 0);
  ::close(pipefd[0]);
  std::ifstream play_err(tmp / "play.stderr");
  std::stringstream play_text;
  play_text << play_err.rdbuf();
  ASSERT_TRUE(WIFEXITED(raw) && WEXITSTATUS(raw) == 0) << play_text.str();
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);

  std::ifstream in(csv);
  std::stringstream got_text;
  got_text << in.rdbuf();
  const std::vector<Row> got = parse_csv(got_text.str());
  ASSERT_EQ(got.size(), want.size()) << got_text.str();
  for (std::size_t i = 0; i < want.size(); ++i) {
    EXPECT_EQ(got[i].change, want[i].change) << "row " << i;
    if (i > 0) {
      EXPECT_GE(got[i].t, got[i - 1].t) << "row " << i;
    }
  }
  // The car ends stopped.
  EXPECT_NE(got_text.str().find("rocker.x"), std::string::npos);
  EXPECT_EQ(expected.value(seqc::emu::RaspblockField::RockerX), 0);
  fs::remove_all(tmp);
}

}  // namespace
