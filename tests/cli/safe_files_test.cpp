// seqc on files a stranger hands it, through the real binary: an output that is one of the
// command's inputs is refused with nothing written (exit 2), a device given as the output stays
// a device, a full disk or a full stdout is exit 5, an include of an endless device is a
// located error at once, an include that is no choreography is located but never quoted, and a
// stop signal ends a command with nothing to stop at once (128 + the signal). In-process: running
// out of memory is exit 70 with a plain message, and a stop signal maps to its exit status.
#include <fcntl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <new>
#include <sstream>
#include <string>
#include <thread>
#include <utility>

#include <gtest/gtest.h>

#include "runtime/cli/app.hpp"
#include "runtime/cli/exit_codes.hpp"
#include "runtime/io/clock.hpp"
#include "tests/cli/seqc_run.hpp"

namespace {

namespace fs = std::filesystem;
using seqc::testing::seqc;
using seqc::testing::SeqcRun;
using seqc::testing::slurp;

// Runs a shell command line with SEQC standing for the binary; its exit status.
int shell(const std::string& line) {
  std::string cmd = line;
  for (std::size_t at; (at = cmd.find("SEQC")) != std::string::npos;) {
    cmd.replace(at, 4, "'" SEQC_BIN "'");
  }
  const int raw = std::system(cmd.c_str());
  return WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
}

class SafeFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    char tmpl[] = "/tmp/seqc-safe-files-XXXXXX";
    ASSERT_NE(::mkdtemp(tmpl), nullptr);
    dir_ = tmpl;
    fs::copy_file(seqc::testing::kSource / "examples/walk.yaml", dir_ / "walk.yaml");
    walk_ = slurp(dir_ / "walk.yaml");
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
  std::string walk_;
};

TEST_F(SafeFiles, OutputOverItsOwnInputIsRefusedAndNothingIsWritten) {
  SeqcRun r = seqc(dir_, "compile walk.yaml -o walk.yaml");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err,
            "seqc: error: -o walk.yaml is the same file as the input walk.yaml; nothing was "
            "written\n");
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(slurp(dir_ / "walk.yaml"), walk_);
}

TEST_F(SafeFiles, OutputOverItsInputThroughAHardOrSymbolicLinkIsRefused) {
  fs::create_hard_link(dir_ / "walk.yaml", dir_ / "hard.yaml");
  fs::create_symlink("walk.yaml", dir_ / "soft.yaml");
  SeqcRun hard = seqc(dir_, "compile walk.yaml -o hard.yaml");
  EXPECT_EQ(hard.status, 2);
  EXPECT_EQ(hard.err,
            "seqc: error: -o hard.yaml is the same file as the input walk.yaml; nothing was "
            "written\n");
  SeqcRun soft = seqc(dir_, "simulate soft.yaml -o walk.yaml");
  EXPECT_EQ(soft.status, 2);
  EXPECT_NE(soft.err.find("seqc: error: -o walk.yaml is the same file as the input soft.yaml; "
                          "nothing was written\n"),
            std::string::npos)
      << soft.err;
  EXPECT_EQ(slurp(dir_ / "walk.yaml"), walk_);
  EXPECT_TRUE(fs::is_symlink(dir_ / "soft.yaml"));
}

TEST_F(SafeFiles, OutputOverAnIncludedFileOrTheSongIsRefused) {
  {
    std::ofstream(dir_ / "part.yaml") << "robot: xarm\nsequence:\n  - move: home\n    time: 1s\n";
    std::ofstream(dir_ / "main.yaml")
        << "name: main\nrobot: xarm\nsequence:\n  - include: part.yaml\n";
  }
  const std::string part = slurp(dir_ / "part.yaml");
  SeqcRun r = seqc(dir_, "compile main.yaml -o part.yaml");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("seqc: error: -o part.yaml is the same file as the input "),
            std::string::npos)
      << r.err;
  EXPECT_EQ(slurp(dir_ / "part.yaml"), part);

  const fs::path examples = seqc::testing::kSource / "examples";
  const std::string song = slurp(examples / "music/neon-pulse.wav");
  SeqcRun plot = seqc(examples, "plot neon-dance.yaml -o music/neon-pulse.wav");
  EXPECT_EQ(plot.status, 2) << plot.err;
  EXPECT_NE(plot.err.find("seqc: error: -o music/neon-pulse.wav is the same file as the input "),
            std::string::npos)
      << plot.err;
  SeqcRun click = seqc(examples, "beats music/neon-pulse.wav --click music/neon-pulse.wav");
  EXPECT_EQ(click.status, 2) << click.err;
  EXPECT_EQ(click.err,
            "seqc: error: --click music/neon-pulse.wav is the same file as the input "
            "music/neon-pulse.wav; nothing was written\n");
  EXPECT_EQ(click.out, "");
  EXPECT_EQ(slurp(examples / "music/neon-pulse.wav"), song);
}

TEST_F(SafeFiles, ADeviceAsTheOutputIsWrittenAndStaysADevice) {
  SeqcRun r = seqc(dir_, "compile walk.yaml -o /dev/null");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out, "");
  struct stat st {};
  ASSERT_EQ(::stat("/dev/null", &st), 0);
  EXPECT_TRUE(S_ISCHR(st.st_mode));
  // /dev/stdout names the test's capture file through /proc: the frames arrive there.
  SeqcRun out = seqc(dir_, "compile walk.yaml -o /dev/stdout");
  EXPECT_EQ(out.status, 0) << out.err;
  EXPECT_EQ(out.out, seqc(dir_, "compile walk.yaml").out);
}

TEST_F(SafeFiles, AFullDiskIsAFileErrorForAFileAndForStdout) {
  const std::string err = (dir_ / "err.txt").string();
  EXPECT_EQ(shell("cd '" + dir_.string() + "' && SEQC compile walk.yaml -o /dev/full 2>" + err), 5);
  EXPECT_EQ(slurp(err), "seqc: error: /dev/full: cannot write: No space left on device\n");
  EXPECT_EQ(shell("cd '" + dir_.string() + "' && SEQC compile walk.yaml >/dev/full 2>" + err), 5);
  EXPECT_EQ(slurp(err), "seqc: error: <stdout>: cannot write: No space left on device\n");
  // A command that writes to stdout as it goes (not through -o) is checked as it ends.
  EXPECT_EQ(shell("cd '" + dir_.string() +
                  "' && SEQC compile walk.yaml | SEQC decode - >/dev/full 2>" + err),
            5);
  EXPECT_NE(slurp(err).find("seqc: error: <stdout>: cannot write"), std::string::npos)
      << slurp(err);
}

TEST_F(SafeFiles, IncludingAnEndlessDeviceIsALocatedErrorAtOnce) {
  std::ofstream(dir_ / "zero.yaml") << "name: zero\nrobot: xarm\nsequence:\n"
                                       "  - include: /dev/zero\n";
  const auto start = std::chrono::steady_clock::now();
  SeqcRun r = seqc(dir_, "check zero.yaml");
  const auto took = std::chrono::steady_clock::now() - start;
  EXPECT_LT(took, std::chrono::seconds(1));
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("zero.yaml:4:14: error: cannot include it: /dev/zero: file is too large "
                       "(more than 16777216 bytes)"),
            std::string::npos)
      << r.err;
}

TEST_F(SafeFiles, EndlessStandardInputIsRefusedAtTheLimit) {
  const std::string err = (dir_ / "err.txt").string();
  const auto start = std::chrono::steady_clock::now();
  EXPECT_EQ(shell("head -c 20000000 /dev/zero | SEQC decode - >/dev/null 2>" + err), 5);
  EXPECT_EQ(shell("head -c 20000000 /dev/zero | SEQC check - >/dev/null 2>>" + err), 5);
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(2));
  EXPECT_EQ(slurp(err),
            "seqc: error: <stdin>: file is too large (more than 16777216 bytes)\n"
            "seqc: error: <stdin>: file is too large (more than 16777216 bytes)\n");
}

// An include that is no choreography file may be any file the user can read: its problem is
// located, but none of its lines reaches the terminal or a SARIF log, nor does a key of it.
TEST_F(SafeFiles, AnIncludeThatIsNoChoreographyIsLocatedButNotQuoted) {
  {
    std::ofstream(dir_ / "shadow") << "root:$6$secret-hash:19000:0:99999:7:::\n"
                                      "daemon:*:19000:0:99999:7:::\n";
    std::ofstream(dir_ / "broken") << "{[secret-flow: 1\n";
    std::ofstream(dir_ / "main.yaml") << "name: main\nrobot: xarm\nsequence:\n"
                                         "  - include: shadow\n  - include: broken\n";
  }
  SeqcRun text = seqc(dir_, "check main.yaml");
  EXPECT_EQ(text.status, 1);
  EXPECT_EQ(text.err.find("secret"), std::string::npos) << text.err;
  EXPECT_NE(text.err.find("shadow:1:1: error: missing 'sequence': the list of steps to perform\n"
                          "main.yaml:4:14: note: included from here\n"
                          "    4 |   - include: shadow\n"),
            std::string::npos)
      << text.err;
  EXPECT_NE(text.err.find("broken:1:2: error: invalid YAML"), std::string::npos) << text.err;
  SeqcRun sarif = seqc(dir_, "check --format sarif main.yaml");
  EXPECT_EQ(sarif.status, 1);
  EXPECT_EQ(sarif.out.find("secret"), std::string::npos) << sarif.out;
  EXPECT_NE(sarif.out.find("\"uri\": \"shadow\""), std::string::npos) << sarif.out;
}

// The stop signals end a command with nothing to stop at once, whatever it was doing: here
// reading an input that never ends (a FIFO whose writer stays open).
TEST_F(SafeFiles, AStopSignalEndsCheckOfASlowInputAtOnce) {
  const fs::path fifo = dir_ / "slow.yaml";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const int writer = ::open(fifo.c_str(), O_RDWR);  // the input never ends while this is open
  ASSERT_GE(writer, 0);
  for (const auto& [signal, status] : {std::pair{SIGTERM, 143}, {SIGINT, 130}, {SIGHUP, 129}}) {
    const pid_t pid = ::fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
      const int null = ::open("/dev/null", O_WRONLY);
      ::dup2(null, STDOUT_FILENO);
      ::dup2(null, STDERR_FILENO);
      ::execl(SEQC_BIN, "seqc", "check", fifo.c_str(), static_cast<char*>(nullptr));
      ::_exit(127);
    }
    // Long enough for seqc to be blocked reading the FIFO, its handlers in place.
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    const auto sent = std::chrono::steady_clock::now();
    ASSERT_EQ(::kill(pid, signal), 0);
    int raw = 0;
    pid_t done = 0;
    while ((done = ::waitpid(pid, &raw, WNOHANG)) == 0 &&
           std::chrono::steady_clock::now() - sent < std::chrono::seconds(5)) {
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    if (done == 0) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, &raw, 0);
      ADD_FAILURE() << "signal " << signal << " did not end seqc check within 5 s";
      continue;
    }
    EXPECT_LT(std::chrono::steady_clock::now() - sent, std::chrono::seconds(1));
    ASSERT_TRUE(WIFEXITED(raw)) << "signal " << signal;
    EXPECT_EQ(WEXITSTATUS(raw), status) << "signal " << signal;
  }
  ::close(writer);
}

// A reader that runs out of memory, as a huge file would on a small machine.
class ExhaustedFiles final : public seqc::FileReader {
 public:
  seqc::Result<std::string> read(const std::string&) override { throw std::bad_alloc(); }
};

TEST(OutOfMemory, IsAnInternalErrorWithAPlainMessage) {
  ExhaustedFiles files;
  seqc::io::ManualClock clock;
  std::ostringstream out, err;
  seqc::cli::Context ctx{out, err, clock, files};
  const char* argv[] = {"seqc", "check", "walk.yaml"};
  EXPECT_EQ(seqc::cli::run(3, argv, ctx), 70);
  EXPECT_EQ(err.str(), "seqc: error: out of memory\n");
}

TEST(StopSignals, EndAsAShellReportsADeathByThem) {
  using seqc::cli::exit_status;
  EXPECT_EQ(exit_status(130, SIGINT), 130);
  EXPECT_EQ(exit_status(130, SIGTERM), 143);
  EXPECT_EQ(exit_status(130, SIGHUP), 129);
  EXPECT_EQ(exit_status(130, 0), 130);
  // A command that finished (or failed) on its own keeps its status whatever arrived.
  EXPECT_EQ(exit_status(0, SIGTERM), 0);
  EXPECT_EQ(exit_status(4, SIGHUP), 4);
}

}  // namespace
