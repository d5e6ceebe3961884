#include "runtime/emulator/pty_server.hpp"

#include <fcntl.h>
#include <poll.h>
#include <sys/prctl.h>
#include <sys/stat.h>
#include <termios.h>
#include <unistd.h>
#include <algorithm>
#include <cerrno>
#include <cstring>

#include <utility>

namespace seqc::emu {
namespace {

// Longest wait between looks at the stop flag.
constexpr io::Duration kStopPoll = std::chrono::milliseconds(50);

std::string errno_text(const std::string& what) { return what + ": " + std::strerror(errno); }

std::optional<speed_t> speed_of(std::uint32_t baud) {
  switch (baud) {
    case 9600:
      return B9600;
    case 19200:
      return B19200;
    case 38400:
      return B38400;
    case 57600:
      return B57600;
    case 115200:
      return B115200;
    case 230400:
      return B230400;
    default:
      return std::nullopt;
  }
}

Status make_link(const std::string& link, const std::string& target) {
  struct stat st {};
  if (::lstat(link.c_str(), &st) == 0) {
    if (!S_ISLNK(st.st_mode)) {
      return make_error("--link " + link + ": exists and is not a symlink; not replacing it");
    }
    if (::unlink(link.c_str()) != 0) return make_error(errno_text("--link " + link));
  }
  if (::symlink(target.c_str(), link.c_str()) != 0) {
    return make_error(errno_text("--link " + link));
  }
  return Ok{};
}

}  // namespace

Result<PtyServer> PtyServer::open(const PtyOptions& options) {
  PtyServer s;
  s.master_ = ::posix_openpt(O_RDWR | O_NOCTTY);
  if (s.master_ < 0) return make_error(errno_text("posix_openpt"));
  if (::grantpt(s.master_) != 0) return make_error(errno_text("grantpt"));
  if (::unlockpt(s.master_) != 0) return make_error(errno_text("unlockpt"));
  char name[128];
  if (::ptsname_r(s.master_, name, sizeof name) != 0) return make_error(errno_text("ptsname"));
  s.slave_path_ = name;
  s.slave_ = ::open(name, O_RDWR | O_NOCTTY);
  if (s.slave_ < 0) return make_error(errno_text("open " + s.slave_path_));

  termios tio{};
  if (::tcgetattr(s.slave_, &tio) != 0) return make_error(errno_text("tcgetattr"));
  ::cfmakeraw(&tio);
  tio.c_cflag |= CLOCAL | CREAD;
  if (auto speed = speed_of(options.baud)) {
    ::cfsetispeed(&tio, *speed);
    ::cfsetospeed(&tio, *speed);
  }
  if (::tcsetattr(s.slave_, TCSANOW, &tio) != 0) return make_error(errno_text("tcsetattr"));

  const int flags = ::fcntl(s.master_, F_GETFL);
  if (flags < 0 || ::fcntl(s.master_, F_SETFL, flags | O_NONBLOCK) != 0) {
    return make_error(errno_text("fcntl"));
  }
  if (options.link) {
    if (auto ok = make_link(*options.link, s.slave_path_); !ok) return ok.error();
    s.link_ = options.link;
  }
  return s;
}

PtyServer::PtyServer(PtyServer&& other) noexcept
    : master_(std::exchange(other.master_, -1)),
      slave_(std::exchange(other.slave_, -1)),
      slave_path_(std::move(other.slave_path_)),
      link_(std::exchange(other.link_, std::nullopt)) {}

PtyServer::~PtyServer() {
  close_fds();
  if (link_) {
    // Remove the link only if it still points at this pty.
    char target[256];
    const ssize_t n = ::readlink(link_->c_str(), target, sizeof target - 1);
    if (n > 0 && std::string(target, static_cast<std::size_t>(n)) == slave_path_) {
      ::unlink(link_->c_str());
    }
  }
}

void PtyServer::close_fds() {
  if (slave_ >= 0) ::close(slave_);
  if (master_ >= 0) ::close(master_);
  slave_ = master_ = -1;
}

Result<PtyServer::Stopped> PtyServer::serve(PtyDevice& device, io::Clock& clock,
                                            const std::atomic<bool>& stop, io::Duration resume) {
  if (master_ < 0) return make_error("the pseudo-terminal is closed");
  // The default timer slack (50 us) would make every timed wake-up late by up to a byte time
  // at 115200 baud; this thread's waits are the emulated line's timing, so ask for none.
  // (Restored on return: the caller's thread keeps its own setting.)
  const int old_slack = ::prctl(PR_GET_TIMERSLACK, 0, 0, 0, 0);
  ::prctl(PR_SET_TIMERSLACK, 1UL, 0, 0, 0);
  struct RestoreSlack {
    int slack;
    ~RestoreSlack() {
      if (slack > 0) ::prctl(PR_SET_TIMERSLACK, static_cast<unsigned long>(slack), 0, 0, 0);
    }
  } restore_slack{old_slack};
  const io::TimePoint origin = clock.now() - resume;
  auto now = [&] { return clock.now() - origin; };
  Bytes pending;  // due output the master could not take yet
  std::uint8_t buf[4096];

  while (!stop.load()) {
    Bytes due = device.take_output(now());
    pending.insert(pending.end(), due.begin(), due.end());
    while (!pending.empty()) {
      const ssize_t n = ::write(master_, pending.data(), pending.size());
      if (n < 0) {
        if (errno == EINTR) continue;
        if (errno == EAGAIN || errno == EWOULDBLOCK) break;
        return make_error(errno_text("write to " + slave_path_));
      }
      pending.erase(pending.begin(), pending.begin() + n);
    }
    if (device.hung_up()) {
      close_fds();
      return Stopped::HangUp;
    }

    io::Duration wait = kStopPoll;
    if (auto next = device.next_output_at()) {
      wait = std::clamp(*next - now(), io::Duration{0}, kStopPoll);
    }
    if (!pending.empty()) wait = std::min(wait, io::Duration{std::chrono::milliseconds(1)});
    pollfd pfd{master_, POLLIN, 0};
    timespec ts{static_cast<time_t>(wait.count() / 1000000000),
                static_cast<long>(wait.count() % 1000000000)};
    const int r = ::ppoll(&pfd, 1, &ts, nullptr);
    if (r < 0) {
      if (errno == EINTR) continue;  // a signal: look at the stop flag
      return make_error(errno_text("poll " + slave_path_));
    }
    if (r > 0 && (pfd.revents & POLLIN)) {
      const ssize_t n = ::read(master_, buf, sizeof buf);
      if (n > 0) {
        device.receive(ByteView(buf, static_cast<std::size_t>(n)), now());
      } else if (n < 0 && errno != EAGAIN && errno != EINTR && errno != EIO) {
        return make_error(errno_text("read from " + slave_path_));
      }
    }
  }
  return Stopped::Requested;
}

}  // namespace seqc::emu
