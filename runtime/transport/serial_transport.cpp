#include "runtime/transport/serial_transport.hpp"

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cstring>
#include <filesystem>
#include <utility>

#include <fcntl.h>
#include <poll.h>
#include <sys/file.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include "runtime/transport/port_messages.hpp"

namespace seqc::transport {
namespace {

bool is_hang_up_errno(int e) { return e == EIO || e == ENXIO || e == ENODEV || e == EPIPE; }

// The /dev/serial/by-id entry that names the device at `path` now, or "" (no such entry: not a
// USB adapter, or udev is not running).
std::string by_id_name(const std::string& path) {
  std::error_code ec;
  const auto device = std::filesystem::canonical(path, ec);
  if (ec) return "";
  for (const auto& entry : std::filesystem::directory_iterator("/dev/serial/by-id", ec)) {
    std::error_code ec2;
    if (std::filesystem::canonical(entry.path(), ec2) == device && !ec2) {
      return entry.path().filename().string();
    }
  }
  return "";
}

// Closes a half-opened port on every early return of open().
struct FdGuard {
  int fd;
  bool exclusive = false;
  ~FdGuard() {
    if (fd < 0) return;
    if (exclusive) ::ioctl(fd, TIOCNXCL);
    ::close(fd);
  }
  int release() { return std::exchange(fd, -1); }
};

std::string errno_text(int e) { return std::strerror(e); }

}  // namespace

int poll_timeout_ms(io::Duration remaining) {
  if (remaining <= io::Duration::zero()) return 0;
  auto ms = std::chrono::ceil<std::chrono::milliseconds>(remaining).count();
  return static_cast<int>(std::min<decltype(ms)>(ms, INT_MAX));
}

io::Duration write_budget(std::size_t bytes, const SerialOptions& options) {
  // 10 bits a byte (8N1), in whole nanoseconds rounded up; exact integers, no float.
  const std::uint64_t bits_ns = static_cast<std::uint64_t>(bytes) * 10u * 1'000'000'000u;
  const std::uint64_t baud = options.baud == 0 ? 1 : options.baud;
  return options.write_slack +
         io::Duration{static_cast<io::Duration::rep>((bits_ns + baud - 1) / baud)};
}

Result<std::unique_ptr<SerialTransport>> SerialTransport::open(const std::string& path,
                                                               io::Clock& clock,
                                                               const SerialOptions& options) {
  auto speed = baud_to_speed(options.baud);
  if (!speed) {
    return make_error("unsupported baud rate " + std::to_string(options.baud) + " for " + path +
                      "; supported: " + supported_baud_list());
  }
  // O_NONBLOCK: neither open() (modem lines) nor any later read or write may block; every
  // wait is a poll() bounded by a deadline.
  FdGuard guard{::open(path.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC)};
  if (guard.fd < 0) {
    int e = errno;
    bool denied = e == EACCES || e == EPERM;
    return make_error(describe_open_errno(path, e, denied ? owning_group(path) : std::nullopt));
  }
  if (!::isatty(guard.fd)) {
    return make_error(path + " is not a serial port or terminal device");
  }
  // flock first: TIOCEXCL does not stop root from opening the port, the lock does.
  if (::flock(guard.fd, LOCK_EX | LOCK_NB) != 0) {
    int e = errno;
    return make_error(e == EWOULDBLOCK ? port_in_use_message(path)
                                       : "cannot lock " + path + ": " + errno_text(e));
  }
  if (::ioctl(guard.fd, TIOCEXCL) != 0) {
    return make_error("cannot take " + path + " exclusively: " + errno_text(errno));
  }
  guard.exclusive = true;

  termios saved{};
  if (::tcgetattr(guard.fd, &saved) != 0) {
    return make_error("cannot read the settings of " + path + ": " + errno_text(errno));
  }
  termios raw = saved;
  ::cfmakeraw(&raw);
  raw.c_cflag &= ~static_cast<tcflag_t>(CSIZE | PARENB | CSTOPB | CRTSCTS);
  raw.c_cflag |= CS8 | CLOCAL | CREAD;
  raw.c_iflag &= ~static_cast<tcflag_t>(IXON | IXOFF | IXANY);
  // VMIN = VTIME = 0: read() returns what is there; waiting is poll()'s job.
  raw.c_cc[VMIN] = 0;
  raw.c_cc[VTIME] = 0;
  ::cfsetispeed(&raw, *speed);
  ::cfsetospeed(&raw, *speed);
  if (::tcsetattr(guard.fd, TCSANOW, &raw) != 0) {
    return make_error("cannot configure " + path + ": " + errno_text(errno));
  }
  // tcsetattr succeeds if any one change was applied, so check the rate took.
  termios applied{};
  if (::tcgetattr(guard.fd, &applied) != 0 || ::cfgetospeed(&applied) != *speed) {
    ::tcsetattr(guard.fd, TCSANOW, &saved);
    return make_error(path + " does not support " + std::to_string(options.baud) + " baud");
  }
  ::tcflush(guard.fd, TCIFLUSH);
  return std::unique_ptr<SerialTransport>(
      new SerialTransport(guard.release(), path, clock, options, saved));
}

SerialTransport::SerialTransport(int fd, std::string path, io::Clock& clock, SerialOptions options,
                                 const termios& saved)
    : fd_(fd),
      path_(std::move(path)),
      clock_(clock),
      options_(options),
      saved_(saved),
      identity_(by_id_name(path_)) {}

bool SerialTransport::reopen(io::TimePoint deadline) {
  for (;;) {
    if (reopen_once()) return true;
    const io::TimePoint now = clock_.now();
    if (now >= deadline) return false;
    clock_.sleep_until(std::min(deadline, now + std::chrono::milliseconds(50)));
  }
}

bool SerialTransport::reopen_once() {
  if (!identity_.empty() && by_id_name(path_) != identity_) return false;  // not back, or not it
  auto again = open(path_, clock_, options_);
  if (!again) return false;
  if (fd_ >= 0) {
    ::flock(fd_, LOCK_UN);
    ::close(fd_);
  }
  fd_ = std::exchange((*again)->fd_, -1);
  saved_ = (*again)->saved_;
  hung_up_ = false;
  return true;
}

SerialTransport::~SerialTransport() {
  if (fd_ < 0) return;  // handed over to a reopened transport
  if (!hung_up_) {
    // Restoring the old settings changes the rate under bytes still in the kernel's output
    // buffer; give them their wire time first, bounded so a stuck device cannot hang exit.
    int pending = 0;
    if (::ioctl(fd_, TIOCOUTQ, &pending) == 0 && pending > 0) {
      auto wire = std::chrono::duration<double>(pending * seconds_per_byte() * 2);
      io::TimePoint limit = clock_.now() + std::chrono::milliseconds(100) +
                            std::chrono::duration_cast<io::Duration>(wire);
      while (::ioctl(fd_, TIOCOUTQ, &pending) == 0 && pending > 0 && clock_.now() < limit) {
        clock_.sleep_until(clock_.now() + std::chrono::milliseconds(1));
      }
    }
  }
  ::tcsetattr(fd_, TCSANOW, &saved_);
  ::ioctl(fd_, TIOCNXCL);
  ::flock(fd_, LOCK_UN);
  ::close(fd_);
}

int SerialTransport::wait_for(short events, io::TimePoint deadline) {
  for (;;) {
    io::TimePoint before = clock_.now();
    pollfd p{fd_, events, 0};
    int r = ::poll(&p, 1, poll_timeout_ms(deadline - before));
    if (r < 0) {
      if (errno == EINTR) continue;
      return -1;
    }
    if (r > 0) return p.revents;
    io::TimePoint after = clock_.now();
    // A clock that did not move while poll waited is not following real time (a test's
    // manual clock): its deadline cannot be reached by waiting, so the wait is over.
    if (after >= deadline || after == before) return 0;
  }
}

io::ReadResult SerialTransport::hang_up(std::string_view doing) const {
  return {io::ReadStatus::HangUp, 0,
          path_ + " hung up while " + std::string(doing) + " (unplugged or closed)"};
}

io::ReadResult SerialTransport::read(std::span<std::uint8_t> buffer, io::TimePoint deadline) {
  if (buffer.empty()) return {io::ReadStatus::Error, 0, "read into an empty buffer"};
  for (;;) {
    int revents = wait_for(POLLIN, deadline);
    if (revents < 0) {
      return {io::ReadStatus::Error, 0, "cannot wait for " + path_ + ": " + errno_text(errno)};
    }
    if (revents == 0) return {io::ReadStatus::Timeout, 0, {}};
    if (revents & POLLNVAL) return {io::ReadStatus::Error, 0, path_ + " is not open"};
    if (revents & POLLIN) {
      ssize_t n = ::read(fd_, buffer.data(), buffer.size());
      if (n > 0) return {io::ReadStatus::Data, static_cast<std::size_t>(n), {}};
      // Readable but nothing to read is end of file: the terminal was hung up.
      if (n == 0) {
        hung_up_ = true;
        return hang_up("reading");
      }
      int e = errno;
      if (e == EINTR || e == EAGAIN) continue;
      if (is_hang_up_errno(e)) {
        hung_up_ = true;
        return hang_up("reading");
      }
      return {io::ReadStatus::Error, 0, "cannot read from " + path_ + ": " + errno_text(e)};
    }
    if (revents & (POLLHUP | POLLERR)) {
      hung_up_ = true;
      return hang_up("reading");
    }
  }
}

// tcdrain returns once the UART (or the USB adapter's driver) has sent everything written.
Status SerialTransport::drain() {
  while (::tcdrain(fd_) != 0) {
    if (errno == EINTR) continue;
    if (is_hang_up_errno(errno)) {
      hung_up_ = true;
      return make_error(hang_up("draining").message);
    }
    return make_error("cannot drain " + path_ + ": " + errno_text(errno));
  }
  return Ok{};
}

Status SerialTransport::write(ByteView bytes) {
  const io::TimePoint deadline = clock_.now() + write_budget(bytes.size(), options_);
  std::size_t done = 0;
  while (done < bytes.size()) {
    ssize_t n = ::write(fd_, bytes.data() + done, bytes.size() - done);
    if (n > 0) {
      done += static_cast<std::size_t>(n);
      continue;
    }
    int e = n < 0 ? errno : EAGAIN;
    if (e == EINTR) continue;
    if (e == EAGAIN) {
      int revents = wait_for(POLLOUT, deadline);
      if (revents < 0) return make_error("cannot wait for " + path_ + ": " + errno_text(errno));
      if (revents == 0) {
        return make_error("timed out writing to " + path_ + " (" + std::to_string(done) + " of " +
                          std::to_string(bytes.size()) +
                          " bytes sent): the device is not accepting data");
      }
      if ((revents & (POLLHUP | POLLERR)) && !(revents & POLLOUT)) {
        hung_up_ = true;
        return make_error(hang_up("writing").message);
      }
      continue;
    }
    if (is_hang_up_errno(e)) {
      hung_up_ = true;
      return make_error(hang_up("writing").message);
    }
    return make_error("cannot write to " + path_ + ": " + errno_text(e));
  }
  return Ok{};
}

void SerialTransport::discard_input() {
  ::tcflush(fd_, TCIFLUSH);
  // Bytes the driver was still handing over during the flush: read them away, bounded so a
  // device streaming without pause cannot keep us here.
  std::uint8_t sink[256];
  for (int i = 0; i < 256; ++i) {
    pollfd p{fd_, POLLIN, 0};
    if (::poll(&p, 1, 0) <= 0 || !(p.revents & POLLIN)) break;
    if (::read(fd_, sink, sizeof sink) <= 0) break;
  }
}

std::string SerialTransport::describe() const {
  return path_ + " at " + std::to_string(options_.baud) + " baud";
}

}  // namespace seqc::transport
