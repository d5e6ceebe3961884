// SerialTransport against real pseudo-terminals: the test is the device on the master side.
#include <atomic>
#include <chrono>
#include <climits>
#include <csignal>
#include <cstring>
#include <functional>
#include <optional>
#include <thread>

#include <fcntl.h>
#include <grp.h>
#include <pthread.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <termios.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include "runtime/io/clock.hpp"
#include "runtime/transport/serial_transport.hpp"
#include "tests/runtime/pty_fixture.hpp"

namespace seqc::transport {
namespace {

using namespace std::chrono_literals;
using testing::Pty;

std::unique_ptr<SerialTransport> open_ok(const std::string& path, io::Clock& clock,
                                         SerialOptions options = {}) {
  auto t = SerialTransport::open(path, clock, options);
  if (!t) ADD_FAILURE() << t.error().message;
  return t ? std::move(*t) : nullptr;
}

io::ReadResult read_into(io::Transport& t, Bytes& out, std::size_t max, io::TimePoint deadline) {
  Bytes buf(max);
  auto r = t.read(buf, deadline);
  if (r.status == io::ReadStatus::Data) out.insert(out.end(), buf.begin(), buf.begin() + r.count);
  return r;
}

// Reads until `count` bytes arrived or something other than data happened.
Bytes read_exactly(io::Transport& t, io::Clock& clock, std::size_t count) {
  Bytes out;
  io::TimePoint deadline = clock.now() + 2s;
  while (out.size() < count) {
    if (read_into(t, out, count - out.size(), deadline).status != io::ReadStatus::Data) break;
  }
  return out;
}

TEST(SerialTransport, RoundTripsRawBytesBothWays) {
  Pty pty;
  io::SteadyClock clock;
  auto t = open_ok(pty.path(), clock);
  ASSERT_TRUE(t);
  // Bytes a cooked terminal would translate or act on: NL, CR, ^C, ^S/^Q, ^D, DEL, 0xFF.
  const Bytes special{0x55, 0x55, 0x0a, 0x0d, 0x03, 0x13, 0x11, 0x04, 0x7f, 0xff, 0x00};
  ASSERT_TRUE(t->write(special).ok());
  EXPECT_EQ(pty.device_reads(special.size(), 1s), special);

  pty.device_writes(special);
  EXPECT_EQ(read_exactly(*t, clock, special.size()), special);
}

TEST(SerialTransport, ConfiguresRaw8N1AtTheRequestedRate) {
  Pty pty;
  io::SteadyClock clock;
  auto t = open_ok(pty.path(), clock, SerialOptions{.baud = 115200});
  ASSERT_TRUE(t);
  termios now{};
  ASSERT_EQ(::tcgetattr(pty.slave(), &now), 0);
  EXPECT_EQ(::cfgetospeed(&now), B115200);
  EXPECT_EQ(::cfgetispeed(&now), B115200);
  EXPECT_EQ(now.c_cflag & CSIZE, static_cast<tcflag_t>(CS8));
  EXPECT_EQ(now.c_cflag & (PARENB | CSTOPB | CRTSCTS), 0u);
  EXPECT_EQ(now.c_lflag & (ICANON | ECHO | ISIG), 0u);
  EXPECT_EQ(now.c_iflag & (IXON | IXOFF | ICRNL), 0u);
  EXPECT_EQ(now.c_oflag & OPOST, 0u);
  EXPECT_EQ(t->describe(), pty.path() + " at 115200 baud");
  EXPECT_DOUBLE_EQ(t->seconds_per_byte(), 10.0 / 115200);
}

TEST(SerialTransport, DefaultsTo9600Baud) {
  Pty pty;
  io::SteadyClock clock;
  auto t = open_ok(pty.path(), clock);
  ASSERT_TRUE(t);
  termios now{};
  ASSERT_EQ(::tcgetattr(pty.slave(), &now), 0);
  EXPECT_EQ(::cfgetospeed(&now), B9600);
  EXPECT_DOUBLE_EQ(t->seconds_per_byte(), 10.0 / 9600);
}

TEST(SerialTransport, RejectsUnsupportedRates) {
  Pty pty;
  io::SteadyClock clock;
  auto t = SerialTransport::open(pty.path(), clock, SerialOptions{.baud = 12345});
  ASSERT_FALSE(t);
  EXPECT_NE(t.error().message.find("unsupported baud rate 12345"), std::string::npos)
      << t.error().message;
  EXPECT_NE(t.error().message.find("115200"), std::string::npos);
}

TEST(SerialTransport, ReadTimesOutAtTheDeadline) {
  Pty pty;
  io::SteadyClock clock;
  auto t = open_ok(pty.path(), clock);
  ASSERT_TRUE(t);
  Bytes buf(16);
  io::TimePoint deadline = clock.now() + 30ms;
  auto r = t->read(buf, deadline);
  EXPECT_EQ(r.status, io::ReadStatus::Timeout);
  EXPECT_EQ(r.count, 0u);
  EXPECT_GE(clock.now(), deadline);
}

// Every wait is one poll() whose timeout comes from the deadline: never early, never negative
// (poll() would wait forever), and no wait at all once the deadline has passed.
TEST(SerialTransport, PollTimeoutsComeFromTheDeadline) {
  EXPECT_EQ(poll_timeout_ms(-1s), 0);
  EXPECT_EQ(poll_timeout_ms(io::Duration::zero()), 0);
  EXPECT_EQ(poll_timeout_ms(1ns), 1);
  EXPECT_EQ(poll_timeout_ms(30ms), 30);
  EXPECT_EQ(poll_timeout_ms(30ms + 1ns), 31);
  EXPECT_EQ(poll_timeout_ms(std::chrono::hours(24 * 365 * 100)), INT_MAX);
}

TEST(SerialTransport, PastDeadlineReturnsAtOnce) {
  Pty pty;
  io::SteadyClock clock;
  auto t = open_ok(pty.path(), clock);
  ASSERT_TRUE(t);
  Bytes buf(16);
  const io::TimePoint before = clock.now();
  EXPECT_EQ(t->read(buf, before - 1s).status, io::ReadStatus::Timeout);
}

TEST(SerialTransport, ManualClockTimeoutDoesNotWaitForever) {
  // A manual clock never reaches the deadline by itself; the read must still end.
  Pty pty;
  io::ManualClock clock;
  auto t = open_ok(pty.path(), clock);
  ASSERT_TRUE(t);
  Bytes buf(16);
  EXPECT_EQ(t->read(buf, clock.now() + 20ms).status, io::ReadStatus::Timeout);
}

TEST(SerialTransport, ClosedMasterIsAHangUpNotATimeout) {
  Pty pty;
  io::SteadyClock clock;
  auto t = open_ok(pty.path(), clock);
  ASSERT_TRUE(t);
  pty.close_master();
  Bytes buf(16);
  auto r = t->read(buf, clock.now() + 5s);
  EXPECT_EQ(r.status, io::ReadStatus::HangUp) << r.message;
  EXPECT_NE(r.message.find(pty.path()), std::string::npos) << r.message;

  auto w = t->write(Bytes{0x55, 0x55, 0x02, 0x0f});
  ASSERT_FALSE(w.ok());
  EXPECT_NE(w.error().message.find("hung up"), std::string::npos) << w.error().message;
}

TEST(SerialTransport, DataBeforeTheHangUpIsStillDelivered) {
  Pty pty;
  io::SteadyClock clock;
  auto t = open_ok(pty.path(), clock);
  ASSERT_TRUE(t);
  pty.device_writes({1, 2, 3});
  // Wait until the bytes reached the slave before the device goes away.
  pollfd p{pty.slave(), POLLIN, 0};
  ASSERT_EQ(::poll(&p, 1, 1000), 1);
  pty.close_master();
  Bytes got;
  auto r = read_into(*t, got, 16, clock.now() + 1s);
  // Linux drops unread input of a hung-up pty on some kernels; either the data or the
  // hang-up is right, a timeout is not.
  EXPECT_NE(r.status, io::ReadStatus::Timeout);
  if (r.status == io::ReadStatus::Data) {
    EXPECT_EQ(got, (Bytes{1, 2, 3}));
    EXPECT_EQ(t->read(got, clock.now() + 1s).status, io::ReadStatus::HangUp);
  }
}

TEST(SerialTransport, SecondOpenFailsAtOnceWithInUseMessage) {
  Pty pty;
  io::SteadyClock clock;
  auto first = open_ok(pty.path(), clock);
  ASSERT_TRUE(first);
  auto second = SerialTransport::open(pty.path(), clock);
  ASSERT_FALSE(second);
  EXPECT_EQ(second.error().message.rfind(pty.path() + " is in use by another program", 0), 0u)
      << second.error().message;

  // Once the first one is closed the port is free again.
  first.reset();
  EXPECT_TRUE(SerialTransport::open(pty.path(), clock).ok());
}

// Runs `fn` in a child process as user and group "nobody" and returns what it printed;
// nothing when this process may not switch users. Root ignores file modes and TIOCEXCL, so the
// tests about them need an unprivileged opener.
std::optional<std::string> as_unprivileged(const std::function<std::string()>& fn) {
  int pipefd[2];
  if (::pipe(pipefd) != 0) return "pipe failed";
  pid_t pid = ::fork();
  if (pid == 0) {
    ::close(pipefd[0]);
    if (::getuid() == 0 &&
        (::setgroups(0, nullptr) != 0 || ::setgid(65534) != 0 || ::setuid(65534) != 0)) {
      _exit(3);
    }
    std::string out = fn();
    (void)!::write(pipefd[1], out.data(), out.size());
    _exit(0);
  }
  ::close(pipefd[1]);
  std::string out;
  char buf[512];
  ssize_t n;
  while ((n = ::read(pipefd[0], buf, sizeof buf)) > 0) {
    out.append(buf, static_cast<std::size_t>(n));
  }
  ::close(pipefd[0]);
  int status = 0;
  ::waitpid(pid, &status, 0);
  if (WIFEXITED(status) && WEXITSTATUS(status) == 3) return std::nullopt;
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) return "child failed";
  return out;
}

TEST(SerialTransport, OtherProgramsAreKeptOutWithTiocexcl) {
  Pty pty;
  ASSERT_EQ(::chmod(pty.path().c_str(), 0666), 0);
  io::SteadyClock clock;
  auto first = open_ok(pty.path(), clock);
  ASSERT_TRUE(first);
  // A program that does not take the lock: a plain open() must fail with EBUSY.
  auto result = as_unprivileged([&] {
    int fd = ::open(pty.path().c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK);
    if (fd >= 0) return std::string("opened");
    return std::string(std::strerror(errno));
  });
  if (!result) GTEST_SKIP() << "cannot switch to an unprivileged user here";
  EXPECT_EQ(*result, std::strerror(EBUSY));
  // And a second seqc run by that user gets the in-use message.
  auto message = as_unprivileged([&] {
    io::SteadyClock child_clock;
    auto t = SerialTransport::open(pty.path(), child_clock);
    return t ? std::string("opened") : t.error().message;
  });
  ASSERT_TRUE(message);
  EXPECT_NE(message->find("is in use by another program"), std::string::npos) << *message;
}

TEST(SerialTransport, PermissionDeniedSaysHowToFixIt) {
  Pty pty;
  ASSERT_EQ(::chmod(pty.path().c_str(), 0600), 0);
  if (::getuid() != 0) {
    ASSERT_EQ(::chmod(pty.path().c_str(), 0000), 0);
  }
  auto message = as_unprivileged([&] {
    io::SteadyClock child_clock;
    auto t = SerialTransport::open(pty.path(), child_clock);
    return t ? std::string("opened") : t.error().message;
  });
  if (!message) GTEST_SKIP() << "cannot switch to an unprivileged user here";
  EXPECT_EQ(message->rfind("permission denied opening " + pty.path(), 0), 0u) << *message;
  EXPECT_NE(message->find("sudo usermod -aG dialout $USER"), std::string::npos) << *message;
}

TEST(SerialTransport, RestoresThePreviousSettingsOnClose) {
  Pty pty;
  termios before{};
  ASSERT_EQ(::tcgetattr(pty.slave(), &before), 0);
  {
    io::SteadyClock clock;
    auto t = open_ok(pty.path(), clock, SerialOptions{.baud = 57600});
    ASSERT_TRUE(t);
    termios during{};
    ASSERT_EQ(::tcgetattr(pty.slave(), &during), 0);
    EXPECT_NE(during.c_lflag, before.c_lflag);  // really changed while open
  }
  termios after{};
  ASSERT_EQ(::tcgetattr(pty.slave(), &after), 0);
  EXPECT_EQ(after.c_iflag, before.c_iflag);
  EXPECT_EQ(after.c_oflag, before.c_oflag);
  EXPECT_EQ(after.c_cflag, before.c_cflag);
  EXPECT_EQ(after.c_lflag, before.c_lflag);
  EXPECT_EQ(std::memcmp(after.c_cc, before.c_cc, sizeof before.c_cc), 0);
  EXPECT_EQ(::cfgetospeed(&after), ::cfgetospeed(&before));
  EXPECT_EQ(::cfgetispeed(&after), ::cfgetispeed(&before));

  // TIOCNXCL: other programs may open the port again.
  int fd = ::open(pty.path().c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK);
  EXPECT_GE(fd, 0);
  if (fd >= 0) ::close(fd);
}

TEST(SerialTransport, DiscardInputDropsStaleBytes) {
  Pty pty;
  io::SteadyClock clock;
  auto t = open_ok(pty.path(), clock);
  ASSERT_TRUE(t);
  pty.device_writes({0x55, 0x55, 0x05, 0x07, 0x00});
  pollfd p{pty.slave(), POLLIN, 0};
  ASSERT_EQ(::poll(&p, 1, 1000), 1);
  t->discard_input();
  Bytes buf(16);
  EXPECT_EQ(t->read(buf, clock.now() + 20ms).status, io::ReadStatus::Timeout);
  pty.device_writes({0xaa});
  EXPECT_EQ(read_exactly(*t, clock, 1), Bytes{0xaa});
}

TEST(SerialTransport, LargeWritesCompleteThroughPartialWrites) {
  Pty pty;
  io::SteadyClock clock;
  auto t = open_ok(pty.path(), clock, SerialOptions{.baud = 4000000});
  ASSERT_TRUE(t);
  // Several times what the pty buffers, so write() sees partial writes and EAGAIN.
  Bytes big(256 * 1024);
  for (std::size_t i = 0; i < big.size(); ++i) big[i] = static_cast<std::uint8_t>(i * 7 + i / 256);
  Bytes received;
  std::thread device([&] { received = pty.device_reads(big.size(), 10s); });
  auto w = t->write(big);
  device.join();
  ASSERT_TRUE(w.ok()) << w.error().message;
  EXPECT_EQ(received, big);
}

TEST(SerialTransport, WriteToADeviceThatStopsReadingTimesOut) {
  Pty pty;
  io::SteadyClock clock;
  auto t = open_ok(pty.path(), clock, SerialOptions{.baud = 4000000, .write_slack = 50ms});
  ASSERT_TRUE(t);
  Bytes big(128 * 1024, 0x55);  // more than the pty holds; nobody reads the master
  const io::TimePoint start = clock.now();
  auto w = t->write(big);
  ASSERT_FALSE(w.ok());
  EXPECT_NE(w.error().message.find("not accepting data"), std::string::npos) << w.error().message;
  // It gave up only once the budget had passed on the clock it was given.
  EXPECT_GE(clock.now() - start,
            write_budget(big.size(), SerialOptions{.baud = 4000000, .write_slack = 50ms}));
}

// 131,072 bytes at 4,000,000 baud (10 bits a byte) take 327.68 ms on the wire.
TEST(SerialTransport, WriteBudgetIsWireTimePlusSlack) {
  EXPECT_EQ(write_budget(128 * 1024, SerialOptions{.baud = 4000000, .write_slack = 50ms}),
            377680us);
  EXPECT_EQ(write_budget(0, SerialOptions{.baud = 9600, .write_slack = 2s}), 2s);
  // 96 bytes at 9600 baud: 100 ms.
  EXPECT_EQ(write_budget(96, SerialOptions{.baud = 9600, .write_slack = 0ms}), 100ms);
}

extern "C" void ignore_signal(int) {}

TEST(SerialTransport, SignalsDuringAWaitDoNotEndIt) {
  Pty pty;
  io::SteadyClock clock;
  auto t = open_ok(pty.path(), clock);
  ASSERT_TRUE(t);
  struct sigaction sa {
  }, old{};
  sa.sa_handler = ignore_signal;  // no SA_RESTART: poll() fails with EINTR
  sigemptyset(&sa.sa_mask);
  ASSERT_EQ(::sigaction(SIGUSR1, &sa, &old), 0);
  pthread_t reader = ::pthread_self();
  std::thread device([&] {
    std::this_thread::sleep_for(10ms);
    ::pthread_kill(reader, SIGUSR1);
    std::this_thread::sleep_for(10ms);
    ::pthread_kill(reader, SIGUSR1);
    std::this_thread::sleep_for(10ms);
    pty.device_writes({0x42});
  });
  Bytes buf(4);
  auto r = t->read(buf, clock.now() + 2s);
  device.join();
  ::sigaction(SIGUSR1, &old, nullptr);
  ASSERT_EQ(r.status, io::ReadStatus::Data) << r.message;
  EXPECT_EQ(buf[0], 0x42);
}

TEST(SerialTransport, NonTerminalsAndMissingPortsAreRefused) {
  io::SteadyClock clock;
  auto null_dev = SerialTransport::open("/dev/null", clock);
  ASSERT_FALSE(null_dev);
  EXPECT_EQ(null_dev.error().message, "/dev/null is not a serial port or terminal device");
  auto missing = SerialTransport::open("/dev/ttyUSB-seqc-missing", clock);
  ASSERT_FALSE(missing);
  EXPECT_EQ(missing.error().message.rfind("no such port /dev/ttyUSB-seqc-missing", 0), 0u)
      << missing.error().message;
}

}  // namespace
}  // namespace seqc::transport
