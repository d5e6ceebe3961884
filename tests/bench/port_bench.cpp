// port_bench: how fast seqc gives up on a port it cannot use. Two figures, each over --runs
// repetitions (default 20), printed with p50 and max against its target:
//
//   busy port   a pseudo-terminal held by SerialTransport in this process (flock + TIOCEXCL,
//               exactly as a first seqc holds it); then `seqc upload tests/data/walk-joints.yaml --port
//               <that pty>` is started with posix_spawn and waited for. Measured: steady_clock
//               from just before posix_spawn to waitpid's return, so process start, dynamic
//               linking and compiling walk.yaml are included. Exit status must be 3 (port
//               unavailable). Target: <= 100 ms.
//   hang-up     SerialTransport open on a pty whose master is then closed (the device
//               unplugged); measured: a read() with a 5 s deadline, from the call to its
//               return, which must report a hang-up. Target: <= 100 ms (reported at once, not
//               at the deadline).
//
// Usage: port_bench [--runs N]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include "runtime/io/clock.hpp"
#include "runtime/transport/serial_transport.hpp"
#include "tests/runtime/pty_fixture.hpp"

extern char** environ;

namespace {

using namespace seqc;
using transport::testing::Pty;
using Wall = std::chrono::steady_clock;

double ms_between(Wall::time_point a, Wall::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

struct Figure {
  std::vector<double> ms;
  int failures = 0;
};

void report(const char* name, Figure f, double target_ms) {
  if (f.ms.empty()) {
    std::printf("%-10s no successful run (%d failed)\n", name, f.failures);
    return;
  }
  std::sort(f.ms.begin(), f.ms.end());
  const double p50 = f.ms[f.ms.size() / 2];
  const double max = f.ms.back();
  std::printf("%-10s %zu runs: p50 %7.2f ms  max %7.2f ms  | target <= %.0f ms: %s%s\n", name,
              f.ms.size(), p50, max, target_ms, max <= target_ms ? "met" : "MISSED",
              f.failures > 0 ? "  (some runs FAILED their functional check)" : "");
}

Figure busy_port(int runs) {
  Figure f;
  const std::string walk = std::string(SEQC_SOURCE_DIR) + "/tests/data/walk-joints.yaml";
  for (int i = 0; i < runs; ++i) {
    Pty pty;
    io::SteadyClock clock;
    auto holder = transport::SerialTransport::open(pty.path(), clock);
    if (!holder) {
      ++f.failures;
      continue;
    }
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&fa, 2, "/dev/null", O_WRONLY, 0);
    const std::string port = pty.path();
    const char* argv[] = {SEQC_BIN, "upload", walk.c_str(), "--port", port.c_str(), nullptr};
    pid_t pid = -1;
    const auto t0 = Wall::now();
    const int rc =
        posix_spawn(&pid, SEQC_BIN, &fa, nullptr, const_cast<char* const*>(argv), environ);
    int status = 0;
    if (rc == 0) ::waitpid(pid, &status, 0);
    const auto t1 = Wall::now();
    posix_spawn_file_actions_destroy(&fa);
    if (rc != 0 || !WIFEXITED(status) || WEXITSTATUS(status) != 3) {
      ++f.failures;
      continue;
    }
    f.ms.push_back(ms_between(t0, t1));
  }
  return f;
}

Figure hang_up(int runs) {
  Figure f;
  for (int i = 0; i < runs; ++i) {
    Pty pty;
    io::SteadyClock clock;
    auto link = transport::SerialTransport::open(pty.path(), clock);
    if (!link) {
      ++f.failures;
      continue;
    }
    pty.close_master();
    std::uint8_t buf[16];
    const auto t0 = Wall::now();
    const auto r = (*link)->read(buf, clock.now() + std::chrono::seconds(5));
    const auto t1 = Wall::now();
    if (r.status != io::ReadStatus::HangUp) {
      ++f.failures;
      continue;
    }
    f.ms.push_back(ms_between(t0, t1));
  }
  return f;
}

}  // namespace

int main(int argc, char** argv) {
  int runs = 20;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--runs" && i + 1 < argc) {
      runs = std::max(1, std::atoi(argv[++i]));
    } else {
      std::fprintf(stderr, "usage: port_bench [--runs N]\n");
      return 2;
    }
  }
  std::printf(
      "port_bench: busy port = posix_spawn .. waitpid of `seqc upload` on a pty this process "
      "holds (exit 3 required); hang-up = read() with a 5 s deadline after the pty master "
      "closed (HangUp required); steady_clock\n");
  const Figure busy = busy_port(runs);
  report("busy port", busy, 100);
  const Figure hup = hang_up(runs);
  report("hang-up", hup, 100);
  return busy.failures + hup.failures == 0 ? 0 : 1;
}
