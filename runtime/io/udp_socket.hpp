// A datagram socket, an OS boundary: `seqc follow --fpp` hears a show's master over UDP and
// answers its discovery pings. Receives take an absolute deadline on the Clock the socket was
// made with, and each datagram carries the instant it was read on that clock, so a fake socket
// on a ManualClock makes a test's timing exact. The real one is IPv4 only, as FPP's MultiSync.
#pragma once

#include <array>
#include <cstdint>
#include <deque>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "base/bytes.hpp"
#include "base/result.hpp"
#include "runtime/io/clock.hpp"

namespace seqc::io {

struct UdpAddress {
  std::array<std::uint8_t, 4> ip{};  // 0.0.0.0: every interface
  std::uint16_t port = 0;
  friend bool operator==(const UdpAddress&, const UdpAddress&) = default;
};

// "192.168.1.10:32320".
std::string address_text(const UdpAddress& address);
// "ADDR[:PORT]" with a dotted IPv4 address; `default_port` when no port is given. Errors are
// sentences ready for "seqc: error: --listen ...".
Result<UdpAddress> parse_udp_address(std::string_view text, std::uint16_t default_port);

struct Datagram {
  Bytes bytes;
  UdpAddress from;
  TimePoint at{0};  // when it reached the socket (the kernel's stamp), on the socket's clock
};

enum class ReceiveStatus { Data, Timeout, Error };
struct Received {
  ReceiveStatus status = ReceiveStatus::Timeout;
  Datagram datagram;    // Data
  std::string message;  // Error
};

class DatagramSocket {
 public:
  virtual ~DatagramSocket() = default;
  // One datagram, waiting until `deadline` for it.
  virtual Received receive(TimePoint deadline) = 0;
  virtual Status send_to(const UdpAddress& to, ByteView bytes) = 0;
  // "udp 0.0.0.0:32320 (multicast 239.70.80.80)".
  virtual std::string describe() const = 0;
};

// Bound to `local` (address reuse on, so FPP on the same machine may share the port), broadcast
// accepted, and, when `group` is given, a member of that multicast group on every interface.
// Its clock must be the steady one the datagrams are dated on.
Result<std::unique_ptr<DatagramSocket>> open_udp_socket(
    const UdpAddress& local, const std::optional<std::array<std::uint8_t, 4>>& group, Clock& clock);

// For tests: datagrams queued with a time are received once the clock reaches it (a receive
// with nothing due sleeps the clock to its deadline, or to the next datagram's time); what is
// sent is recorded.
class FakeDatagramSocket final : public DatagramSocket {
 public:
  explicit FakeDatagramSocket(ManualClock& clock) : clock_(clock) {}
  void arrive(TimePoint at, Bytes bytes, UdpAddress from = {{192, 168, 1, 10}, 32320}) {
    queue_.push_back({std::move(bytes), from, at});
  }
  Received receive(TimePoint deadline) override;
  Status send_to(const UdpAddress& to, ByteView bytes) override {
    sent.push_back({Bytes(bytes.begin(), bytes.end()), to, clock_.now()});
    return Ok{};
  }
  std::string describe() const override { return "udp (fake)"; }
  bool drained() const { return queue_.empty(); }

  std::vector<Datagram> sent;  // `from` holds the destination

 private:
  ManualClock& clock_;
  std::deque<Datagram> queue_;
};

}  // namespace seqc::io
