#include "runtime/io/udp_socket.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/uio.h>
#include <time.h>
#include <unistd.h>
#include <cerrno>
#include <cstring>

#include <algorithm>
#include <charconv>

namespace seqc::io {
namespace {

std::string ip_text(const std::array<std::uint8_t, 4>& ip) {
  return std::to_string(ip[0]) + "." + std::to_string(ip[1]) + "." + std::to_string(ip[2]) + "." +
         std::to_string(ip[3]);
}

sockaddr_in to_sockaddr(const UdpAddress& a) {
  sockaddr_in s{};
  s.sin_family = AF_INET;
  s.sin_port = htons(a.port);
  std::memcpy(&s.sin_addr.s_addr, a.ip.data(), 4);  // already in network order
  return s;
}

class UdpSocket final : public DatagramSocket {
 public:
  UdpSocket(int fd, std::string what, Clock& clock)
      : fd_(fd), what_(std::move(what)), clock_(clock) {}
  ~UdpSocket() override { ::close(fd_); }
  UdpSocket(const UdpSocket&) = delete;
  UdpSocket& operator=(const UdpSocket&) = delete;

  Received receive(TimePoint deadline) override {
    Received r;
    for (;;) {
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
          deadline - clock_.now() + std::chrono::microseconds(999));
      pollfd p{fd_, POLLIN, 0};
      const int n = ::poll(&p, 1, static_cast<int>(std::max<std::int64_t>(0, left.count())));
      if (n < 0 && errno == EINTR) {
        if (clock_.now() >= deadline) return r;
        continue;
      }
      if (n < 0) return {ReceiveStatus::Error, {}, std::strerror(errno)};
      if (n == 0) return r;
      sockaddr_in from{};
      iovec io{buffer_.data(), buffer_.size()};
      alignas(cmsghdr) std::array<char, CMSG_SPACE(sizeof(timespec))> control{};
      msghdr m{};
      m.msg_name = &from;
      m.msg_namelen = sizeof from;
      m.msg_iov = &io;
      m.msg_iovlen = 1;
      m.msg_control = control.data();
      m.msg_controllen = control.size();
      const ssize_t got = ::recvmsg(fd_, &m, 0);
      if (got < 0 && (errno == EINTR || errno == EAGAIN)) continue;
      if (got < 0) return {ReceiveStatus::Error, {}, std::strerror(errno)};
      r.status = ReceiveStatus::Data;
      r.datagram.at = clock_.now() - waited(m);
      // The buffer holds the largest UDP datagram, so none is cut.
      r.datagram.bytes.assign(buffer_.begin(), buffer_.begin() + got);
      std::memcpy(r.datagram.from.ip.data(), &from.sin_addr.s_addr, 4);
      r.datagram.from.port = ntohs(from.sin_port);
      return r;
    }
  }

  Status send_to(const UdpAddress& to, ByteView bytes) override {
    const sockaddr_in s = to_sockaddr(to);
    const ssize_t n = ::sendto(fd_, bytes.data(), bytes.size(), 0,
                               reinterpret_cast<const sockaddr*>(&s), sizeof s);
    if (n < 0) return make_error("sending to " + address_text(to) + ": " + std::strerror(errno));
    return Ok{};
  }

  std::string describe() const override { return what_; }

 private:
  // How long the datagram waited in the socket since the kernel took it (SO_TIMESTAMPNS, on the
  // real-time clock, compared with the real-time clock now): a datagram read late, after a long
  // upload, is still dated when it came. 0 without a stamp.
  static Duration waited(msghdr& m) {
    for (cmsghdr* c = CMSG_FIRSTHDR(&m); c != nullptr; c = CMSG_NXTHDR(&m, c)) {
      if (c->cmsg_level != SOL_SOCKET || c->cmsg_type != SCM_TIMESTAMPNS) continue;
      timespec stamp{};
      std::memcpy(&stamp, CMSG_DATA(c), sizeof stamp);
      timespec now{};
      ::clock_gettime(CLOCK_REALTIME, &now);
      const auto ns = [](const timespec& t) {
        return static_cast<std::int64_t>(t.tv_sec) * 1'000'000'000 + t.tv_nsec;
      };
      return Duration{std::max<std::int64_t>(0, ns(now) - ns(stamp))};
    }
    return Duration{0};
  }

  std::array<std::uint8_t, 65536> buffer_{};
  int fd_;
  std::string what_;
  Clock& clock_;
};

}  // namespace

std::string address_text(const UdpAddress& address) {
  return ip_text(address.ip) + ":" + std::to_string(address.port);
}

Result<UdpAddress> parse_udp_address(std::string_view text, std::uint16_t default_port) {
  UdpAddress a;
  a.port = default_port;
  std::string_view host = text;
  if (const auto colon = text.find(':'); colon != std::string_view::npos) {
    host = text.substr(0, colon);
    const std::string_view port = text.substr(colon + 1);
    unsigned value = 0;
    const auto [end, ec] = std::from_chars(port.data(), port.data() + port.size(), value);
    if (ec != std::errc{} || end != port.data() + port.size() || value == 0 || value > 65535) {
      return make_error("'" + std::string(text) + "': the port must be a number from 1 to 65535");
    }
    a.port = static_cast<std::uint16_t>(value);
  }
  in_addr parsed{};
  if (::inet_pton(AF_INET, std::string(host).c_str(), &parsed) != 1) {
    return make_error("'" + std::string(text) +
                      "' is not an IPv4 address (as 127.0.0.1 or 0.0.0.0:32320)");
  }
  std::memcpy(a.ip.data(), &parsed.s_addr, 4);
  return a;
}

Result<std::unique_ptr<DatagramSocket>> open_udp_socket(
    const UdpAddress& local, const std::optional<std::array<std::uint8_t, 4>>& group,
    Clock& clock) {
  const int fd = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  if (fd < 0) return make_error(std::string("cannot make a UDP socket: ") + std::strerror(errno));
  const auto failed = [&](const std::string& what) -> Error {
    const std::string why = std::strerror(errno);
    ::close(fd);
    return make_error(what + ": " + why);
  };
  const int on = 1;
  if (::setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &on, sizeof on) != 0 ||
      ::setsockopt(fd, SOL_SOCKET, SO_BROADCAST, &on, sizeof on) != 0 ||
      ::setsockopt(fd, SOL_SOCKET, SO_TIMESTAMPNS, &on, sizeof on) != 0) {
    return failed("cannot set the UDP socket's options");
  }
  const sockaddr_in s = to_sockaddr(local);
  if (::bind(fd, reinterpret_cast<const sockaddr*>(&s), sizeof s) != 0) {
    return failed("cannot listen on udp " + address_text(local));
  }
  std::string what = "udp " + address_text(local);
  if (group) {
    ip_mreq m{};
    std::memcpy(&m.imr_multiaddr.s_addr, group->data(), 4);
    m.imr_interface.s_addr = htonl(INADDR_ANY);
    // A machine without a multicast route still hears broadcast and unicast: not fatal.
    if (::setsockopt(fd, IPPROTO_IP, IP_ADD_MEMBERSHIP, &m, sizeof m) == 0) {
      what += " (multicast " + ip_text(*group) + ")";
    } else {
      what += " (not in multicast " + ip_text(*group) + ": " + std::strerror(errno) + ")";
    }
  }
  return std::unique_ptr<DatagramSocket>(std::make_unique<UdpSocket>(fd, what, clock));
}

Received FakeDatagramSocket::receive(TimePoint deadline) {
  if (!queue_.empty() && queue_.front().at <= deadline) {
    clock_.sleep_until(queue_.front().at);
    Received r;
    r.status = ReceiveStatus::Data;
    r.datagram = std::move(queue_.front());
    queue_.pop_front();
    r.datagram.at = clock_.now();
    return r;
  }
  clock_.sleep_until(deadline);
  return {};
}

}  // namespace seqc::io
