// The pseudo-terminal server, run in a thread, spoken to through the slave tty like a serial
// port. This is the one emulator test on real time: it waits on poll() with a generous
// deadline, never sleeps.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <poll.h>
#include <termios.h>
#include <unistd.h>
#include <atomic>
#include <thread>

#include <chrono>
#include <condition_variable>
#include <filesystem>
#include <mutex>
#include <sstream>

#include "runtime/emulator/pty_server.hpp"
#include "tests/emulator/emu_test_util.hpp"

namespace seqc::emu::test {
namespace {

int open_raw(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDWR | O_NOCTTY);
  if (fd < 0) return fd;
  termios tio{};
  ::tcgetattr(fd, &tio);
  ::cfmakeraw(&tio);
  ::cfsetispeed(&tio, B9600);
  ::cfsetospeed(&tio, B9600);
  ::tcsetattr(fd, TCSANOW, &tio);
  return fd;
}

// Reads until `n` bytes came, the line hangs up or 5 s pass.
Bytes read_bytes(int fd, std::size_t n) {
  Bytes out;
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (out.size() < n) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        give_up - std::chrono::steady_clock::now());
    if (left.count() <= 0) break;
    pollfd pfd{fd, POLLIN, 0};
    if (::poll(&pfd, 1, static_cast<int>(left.count())) <= 0) break;
    std::uint8_t buf[64];
    const ssize_t got = ::read(fd, buf, sizeof buf);
    if (got <= 0) break;
    out.insert(out.end(), buf, buf + got);
  }
  return out;
}

class Served {
 public:
  Served(PtyServer& server, PtyDevice& device) {
    thread_ = std::thread([&] {
      auto outcome = server.serve(device, clock_, stop_);
      std::lock_guard lock(mu_);
      outcome_ = std::move(outcome);
      done_ = true;
      cv_.notify_all();
    });
  }
  ~Served() { (void)finish(); }
  // Asks the server to stop and waits for it.
  Result<PtyServer::Stopped> finish() {
    stop_ = true;
    if (thread_.joinable()) thread_.join();
    return outcome_;
  }
  // Waits up to 5 s for the server to stop by itself (then stops it: a test failure).
  Result<PtyServer::Stopped> wait_until_stopped() {
    {
      std::unique_lock lock(mu_);
      if (!cv_.wait_for(lock, std::chrono::seconds(5), [&] { return done_; })) {
        lock.unlock();
        (void)finish();
        return make_error("the server did not stop by itself within 5 s");
      }
    }
    return finish();
  }

 private:
  io::SteadyClock clock_;
  std::atomic<bool> stop_{false};
  std::mutex mu_;
  std::condition_variable cv_;
  bool done_ = false;
  Result<PtyServer::Stopped> outcome_ = make_error("not run");
  std::thread thread_;
};

TEST(PtyServer, XArmRoundTripThroughTheSlaveTty) {
  const std::string link = ::testing::TempDir() + "/seqc-emu-link-" + std::to_string(::getpid());
  PtyOptions options;
  options.baud = 9600;
  options.link = link;
  XArmConfig config;
  config.baud = 9600;
  XArmEmulator emu(config);
  {
    auto server = PtyServer::open(options);
    ASSERT_TRUE(server.ok()) << server.error().message;
    EXPECT_EQ(std::filesystem::read_symlink(link).string(), server->slave_path());

    ControllerPtyDevice device(emu);
    {
      Served served(*server, device);
      const int fd = open_raw(link);
      ASSERT_GE(fd, 0);
      const Bytes request = hex("55 55 02 0f 55 55 05 15 02 01 06");
      ASSERT_EQ(::write(fd, request.data(), request.size()), static_cast<ssize_t>(request.size()));
      EXPECT_EQ(hex_of(read_bytes(fd, 17)), "55 55 04 0f 4c 1d 55 55 09 15 02 01 f4 01 06 f4 01");
      ::close(fd);
      auto outcome = served.finish();
      ASSERT_TRUE(outcome.ok()) << outcome.error().message;
      EXPECT_EQ(*outcome, PtyServer::Stopped::Requested);
    }
    EXPECT_EQ(emu.received_bytes(), hex("55 55 02 0f 55 55 05 15 02 01 06"));
    ASSERT_EQ(emu.received().size(), 2u);
  }  // the server is gone: so is the link
  EXPECT_FALSE(std::filesystem::exists(std::filesystem::symlink_status(link)));
}

// A pty hands the host's bytes over at once; the server must still not let the controller
// see a frame before its wire time, nor answer before the reply's wire time: request and
// reply together are 10 bytes, 10.4 ms at 9600 baud, however fast the machine is.
TEST(PtyServer, XArmAnswersNoSoonerThanBothDirectionsTakeOnTheWire) {
  auto server = PtyServer::open({9600, std::nullopt});
  ASSERT_TRUE(server.ok()) << server.error().message;
  XArmConfig config;
  config.baud = 9600;
  XArmEmulator emu(config);
  ControllerPtyDevice device(emu);
  Served served(*server, device);
  const int fd = open_raw(server->slave_path());
  ASSERT_GE(fd, 0);
  const Bytes request = hex("55 55 02 0f");
  const auto t0 = std::chrono::steady_clock::now();
  ASSERT_EQ(::write(fd, request.data(), request.size()), 4);
  EXPECT_EQ(hex_of(read_bytes(fd, 6)), "55 55 04 0f 4c 1d");
  const auto took = std::chrono::steady_clock::now() - t0;
  EXPECT_GE(took, std::chrono::microseconds(10 * 1'041'666 / 1000)) << "4 bytes in + 6 out";
  ::close(fd);
  ASSERT_TRUE(served.finish().ok());
}

TEST(PtyServer, HangUpClosesTheLink) {
  auto server = PtyServer::open({});
  ASSERT_TRUE(server.ok()) << server.error().message;
  XArmConfig config;
  config.faults.hangup_at = 2;
  XArmEmulator emu(config);
  ControllerPtyDevice device(emu);
  Served served(*server, device);
  const int fd = open_raw(server->slave_path());
  ASSERT_GE(fd, 0);
  const Bytes one = hex("55 55 02 0f");
  ASSERT_EQ(::write(fd, one.data(), one.size()), 4);
  EXPECT_EQ(read_bytes(fd, 6).size(), 6u);
  ASSERT_EQ(::write(fd, one.data(), one.size()), 4);
  auto outcome = served.wait_until_stopped();
  ASSERT_TRUE(outcome.ok()) << outcome.error().message;
  EXPECT_EQ(*outcome, PtyServer::Stopped::HangUp);
  // The client sees the line go away: poll reports a hang-up and read gives no data.
  pollfd pfd{fd, POLLIN, 0};
  ASSERT_EQ(::poll(&pfd, 1, 1000), 1);
  EXPECT_NE(pfd.revents & (POLLHUP | POLLERR), 0);
  std::uint8_t buf[8];
  EXPECT_LE(::read(fd, buf, sizeof buf), 0);
  ::close(fd);
}

// Forwards to a device and lets the test wait (on a condition variable, with a deadline)
// until a number of bytes has been received, since the Raspblock never answers.
class CountingDevice final : public PtyDevice {
 public:
  explicit CountingDevice(PtyDevice& inner) : inner_(inner) {}
  void receive(ByteView bytes, io::TimePoint at) override {
    inner_.receive(bytes, at);
    std::lock_guard lock(mu_);
    count_ += bytes.size();
    cv_.notify_all();
  }
  std::optional<io::TimePoint> next_output_at() const override { return inner_.next_output_at(); }
  Bytes take_output(io::TimePoint upto) override { return inner_.take_output(upto); }
  bool hung_up() const override { return inner_.hung_up(); }
  bool wait_for(std::size_t n) {
    std::unique_lock lock(mu_);
    return cv_.wait_for(lock, std::chrono::seconds(5), [&] { return count_ >= n; });
  }

 private:
  PtyDevice& inner_;
  std::mutex mu_;
  std::condition_variable cv_;
  std::size_t count_ = 0;
};

TEST(PtyServer, RaspblockStateChangesPrinted) {
  auto server = PtyServer::open({115200, std::nullopt});
  ASSERT_TRUE(server.ok()) << server.error().message;
  RaspblockEmulator board;
  std::ostringstream log;
  RaspblockPtyDevice inner(board, &log);
  CountingDevice device(inner);
  Served served(*server, device);
  const int fd = open_raw(server->slave_path());
  ASSERT_GE(fd, 0);
  // Servo 3 to 2000, then the same packet with a bad checksum.
  const Bytes packets = hex("ff fe 02 03 03 07 d0 df ff fe 02 03 03 07 d0 de");
  ASSERT_EQ(::write(fd, packets.data(), packets.size()), 16);
  ASSERT_TRUE(device.wait_for(16));
  ::close(fd);
  ASSERT_TRUE(served.finish().ok());
  EXPECT_EQ(board.received_bytes(), packets);
  EXPECT_EQ(board.packets().size(), 1u);
  EXPECT_EQ(board.bad_checksums(), 1u);
  const std::string text = log.str();
  EXPECT_NE(text.find(" s  servo.3 = 2000\n"), std::string::npos) << text;
  EXPECT_NE(text.find("rejected: "), std::string::npos) << text;
}

}  // namespace
}  // namespace seqc::emu::test
