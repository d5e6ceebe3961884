// A serial port (USB serial adapter, UART) or pseudo-terminal as an io::Transport, with POSIX
// termios: raw 8N1, no flow control, non-blocking I/O waited on with poll() until deadlines
// taken from the injected clock.
//
// Opening takes the port exclusively twice over: flock(LOCK_EX|LOCK_NB), which a second seqc
// always sees (even as root), and TIOCEXCL, which makes other programs' open() fail with EBUSY.
// Either way the second opener fails at once with "PATH is in use by another program".
// The port's previous termios settings are restored when the transport is destroyed.
//
// After a hang-up, reopen() opens the same path again (polling until its deadline) with the
// same settings, but only the same device: a USB adapter is known by its /dev/serial/by-id name
// (vendor, product, serial number), taken when the port was first opened; if another adapter
// takes the path meanwhile, reopen() waits on. Ports without such a name (UARTs, pseudo-
// terminals, a symlink of the user's) are known by their path.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include <termios.h>

#include "runtime/io/clock.hpp"
#include "runtime/io/transport.hpp"
#include "runtime/transport/baud_rates.hpp"

namespace seqc::transport {

struct SerialOptions {
  std::uint32_t baud = kDefaultBaud;
  // How long write() waits for the kernel to accept more bytes, on top of the time the bytes
  // need on the wire. A device that stops draining its buffer fails the write after this.
  io::Duration write_slack = std::chrono::seconds(2);
};

// The timeout for one poll() that must not return before `remaining` has passed: whole
// milliseconds rounded up, 0 once the deadline has passed.
int poll_timeout_ms(io::Duration remaining);

// How long writing `bytes` may take before the device counts as not accepting data: the time
// the bytes need on the wire at the port's rate plus the options' slack.
io::Duration write_budget(std::size_t bytes, const SerialOptions& options);

class SerialTransport final : public io::Transport {
 public:
  // Opens and configures `path`. Errors are complete sentences for the user: in use, permission
  // denied (with the fix), no such port, not a terminal, unsupported baud rate.
  static Result<std::unique_ptr<SerialTransport>> open(const std::string& path, io::Clock& clock,
                                                       const SerialOptions& options = {});

  ~SerialTransport() override;
  SerialTransport(const SerialTransport&) = delete;
  SerialTransport& operator=(const SerialTransport&) = delete;

  Status write(ByteView bytes) override;
  io::ReadResult read(std::span<std::uint8_t> buffer, io::TimePoint deadline) override;
  void discard_input() override;
  std::string describe() const override;
  double seconds_per_byte() const override { return 10.0 / options_.baud; }
  Status drain() override;
  bool reopen(io::TimePoint deadline) override;

  const std::string& path() const { return path_; }

 private:
  SerialTransport(int fd, std::string path, io::Clock& clock, SerialOptions options,
                  const termios& saved);

  // Waits for `events` on the port until `deadline`; returns poll's revents, 0 on timeout,
  // -1 with errno on failure.
  int wait_for(short events, io::TimePoint deadline);
  io::ReadResult hang_up(std::string_view doing) const;
  // One attempt of reopen().
  bool reopen_once();

  int fd_;
  std::string path_;
  io::Clock& clock_;
  SerialOptions options_;
  termios saved_;
  bool hung_up_ = false;
  std::string identity_;  // the /dev/serial/by-id name of the device, or ""
};

}  // namespace seqc::transport
