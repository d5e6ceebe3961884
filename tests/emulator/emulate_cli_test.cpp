// `seqc emulate` as a user runs it: the real binary in a child process, spoken to through the
// pseudo-terminal it prints, stopped with SIGINT. Waits use poll() with deadlines, no sleeps.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <termios.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "base/bytes.hpp"

extern char** environ;

namespace {

using Clock = std::chrono::steady_clock;

struct Child {
  pid_t pid = -1;
  int out = -1;          // the child's stdout
  int err = -1;          // the child's stderr
  std::string err_text;  // stderr read so far
};

Child spawn_seqc(const std::vector<std::string>& args) {
  int out_fds[2];
  int err_fds[2];
  EXPECT_EQ(::pipe(out_fds), 0);
  EXPECT_EQ(::pipe(err_fds), 0);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, out_fds[1], STDOUT_FILENO);
  posix_spawn_file_actions_adddup2(&actions, err_fds[1], STDERR_FILENO);
  posix_spawn_file_actions_addclose(&actions, out_fds[0]);
  posix_spawn_file_actions_addclose(&actions, err_fds[0]);
  std::vector<std::string> argv_s = {SEQC_BINARY};
  argv_s.insert(argv_s.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : argv_s) argv.push_back(a.data());
  argv.push_back(nullptr);
  Child c;
  EXPECT_EQ(posix_spawn(&c.pid, SEQC_BINARY, &actions, nullptr, argv.data(), environ), 0);
  posix_spawn_file_actions_destroy(&actions);
  ::close(out_fds[1]);
  ::close(err_fds[1]);
  c.out = out_fds[0];
  c.err = err_fds[0];
  return c;
}

// Appends what `fd` gives to `acc` until `done(acc)` or end of file or 10 s.
template <class Done>
void read_until(int fd, std::string& acc, Done done) {
  const auto give_up = Clock::now() + std::chrono::seconds(10);
  while (!done(acc)) {
    const auto left =
        std::chrono::duration_cast<std::chrono::milliseconds>(give_up - Clock::now()).count();
    if (left <= 0) return;
    pollfd pfd{fd, POLLIN, 0};
    if (::poll(&pfd, 1, static_cast<int>(left)) <= 0) return;
    char buf[256];
    const ssize_t got = ::read(fd, buf, sizeof buf);
    if (got <= 0) return;
    acc.append(buf, static_cast<std::size_t>(got));
  }
}

// The first line of the child's stdout ("" if none within 10 s).
std::string read_line(int fd) {
  std::string acc;
  read_until(fd, acc, [](const std::string& a) { return a.find('\n') != std::string::npos; });
  const auto nl = acc.find('\n');
  return nl == std::string::npos ? "" : acc.substr(0, nl);
}

seqc::Bytes read_bytes(int fd, std::size_t n) {
  std::string acc;
  read_until(fd, acc, [n](const std::string& a) { return a.size() >= n; });
  return seqc::Bytes(acc.begin(), acc.end());
}

// Reads the child's stderr to its end (the child closing it means it is exiting), then reaps
// it. Returns the exit status, or -1 if it had to be killed after 10 s.
int wait_exit(Child& c) {
  read_until(c.err, c.err_text, [](const std::string&) { return false; });
  pollfd pfd{c.err, POLLIN, 0};
  char probe = 0;
  const bool ended = ::poll(&pfd, 1, 0) == 1 && ::read(c.err, &probe, 1) == 0;
  if (!ended) ::kill(c.pid, SIGKILL);
  int status = 0;
  ::waitpid(c.pid, &status, 0);
  ::close(c.out);
  ::close(c.err);
  return ended && WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

int open_raw(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDWR | O_NOCTTY);
  if (fd < 0) return fd;
  termios tio{};
  ::tcgetattr(fd, &tio);
  ::cfmakeraw(&tio);
  ::tcsetattr(fd, TCSANOW, &tio);
  return fd;
}

const std::string kTmp = ::testing::TempDir() + "/seqc-emulate-" + std::to_string(::getpid());

TEST(EmulateCommand, XArmServesRepliesAndRecordsUntilSigint) {
  const std::string record = kTmp + "-xarm.csv";
  Child c = spawn_seqc({"emulate", "xarm", "--record", record});
  const std::string slave = read_line(c.out);
  ASSERT_EQ(slave.rfind("/dev/pts/", 0), 0u) << slave;
  const int fd = open_raw(slave);
  ASSERT_GE(fd, 0);
  const seqc::Bytes request = *seqc::parse_hex("55 55 02 0f");
  ASSERT_EQ(::write(fd, request.data(), request.size()), 4);
  EXPECT_EQ(seqc::to_hex(read_bytes(fd, 6)), "55 55 04 0f 4c 1d");
  ::close(fd);
  ::kill(c.pid, SIGINT);
  EXPECT_EQ(wait_exit(c), 0);
  const std::string csv = slurp(record);
  EXPECT_EQ(csv.rfind("time_s,status,bytes,message\n", 0), 0u) << csv;
  EXPECT_NE(csv.find(",ok,55 55 02 0f,GetBatteryVoltage\n"), std::string::npos) << csv;
  EXPECT_EQ(c.err_text, "seqc: emulating an xArm controller on " + slave +
                            " (9600 baud, faults: none); Ctrl-C to stop\n"
                            "seqc: received 1 frames, 4 bytes\n");
}

TEST(EmulateCommand, XArmHangUpFaultEndsTheRun) {
  Child c = spawn_seqc({"emulate", "xarm", "--baud", "0", "--faults", "hangup-at=1"});
  const std::string slave = read_line(c.out);
  const int fd = open_raw(slave);
  ASSERT_GE(fd, 0);
  const seqc::Bytes request = *seqc::parse_hex("55 55 02 0f");
  ASSERT_EQ(::write(fd, request.data(), request.size()), 4);
  EXPECT_EQ(wait_exit(c), 0);
  ::close(fd);
  EXPECT_NE(c.err_text.find("seqc: emulated hang-up at frame 1 (--faults hangup-at)\n"),
            std::string::npos)
      << c.err_text;
}

TEST(EmulateCommand, RaspblockPrintsStateChangesAndWritesTimeline) {
  const std::string record = kTmp + "-rasp.csv";
  Child c = spawn_seqc({"emulate", "raspblock", "--record", record});
  const std::string slave = read_line(c.out);
  const int fd = open_raw(slave);
  ASSERT_GE(fd, 0);
  const seqc::Bytes packet = *seqc::parse_hex("ff fe 02 03 03 07 d0 df");
  ASSERT_EQ(::write(fd, packet.data(), packet.size()), 8);
  // The board never answers: wait for the change to show on stderr.
  read_until(c.err, c.err_text,
             [](const std::string& a) { return a.find("servo.3") != std::string::npos; });
  ::close(fd);
  ::kill(c.pid, SIGTERM);
  EXPECT_EQ(wait_exit(c), 0);
  EXPECT_NE(c.err_text.find(" s  servo.3 = 2000\n"), std::string::npos) << c.err_text;
  EXPECT_NE(c.err_text.find("seqc: received 1 packets, 0 rejected (0 bad checksums)\n"),
            std::string::npos)
      << c.err_text;
  const std::string csv = slurp(record);
  EXPECT_EQ(csv.rfind("time_s,field,previous,value\n", 0), 0u) << csv;
  EXPECT_NE(csv.find(",servo.3,,2000\n"), std::string::npos) << csv;
}

TEST(EmulateCommand, UsageErrors) {
  Child c = spawn_seqc({"emulate", "xarm", "--faults", "dorp=0.1"});
  EXPECT_EQ(wait_exit(c), 2);
  EXPECT_EQ(c.err_text,
            "seqc: error: --faults: unknown fault 'dorp'; did you mean 'drop'? (known: seed, "
            "drop, corrupt, late, late-by, dup, silent-after, hangup-at, back-after, reset, "
            "reset-at, boot-time, busy, busy-for, frame-gap, split, clock)\n");
  Child r = spawn_seqc({"emulate", "raspblock", "--faults", "drop=0.1"});
  EXPECT_EQ(wait_exit(r), 2);
  EXPECT_EQ(r.err_text,
            "seqc: error: --faults and --seed apply to the xarm emulator only (the Raspblock "
            "board never replies)\n");
}

TEST(EmulateCommand, HelpMatchesGolden) {
  Child c = spawn_seqc({"emulate", "--help"});
  std::string out;
  read_until(c.out, out, [](const std::string&) { return false; });
  EXPECT_EQ(wait_exit(c), 0);
  EXPECT_EQ(out, slurp(std::string(SEQC_SOURCE_DIR) + "/tests/emulator/golden/emulate-help.txt"));
}

}  // namespace
