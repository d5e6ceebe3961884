// Serves an emulated device on a pseudo-terminal, so any program (seqc itself, a vendor tool,
// a terminal) can open the slave side like a serial port.
//
// open() creates the pty (posix_openpt), puts the slave in raw mode (8N1, no echo, no line
// editing) and, if asked, points a symlink at the slave. The server keeps a slave descriptor
// open itself, so clients may come and go without the master seeing a hang-up.
// serve() reads bytes from the master with poll, feeds them to the device stamped with the
// clock's time (relative to the start of serve(), so the device's times begin near 0), and
// writes the device's output when it is due, until `stop` becomes true or the device hangs
// up (then both sides are closed: the client sees the link go away). It sleeps until the
// device's next_output_at() (the device's line timing, e.g. the xArm's receive line, is the
// device's business: see pty_device.hpp) or until the host writes, with no timer slack.
#pragma once

#include <atomic>
#include <cstdint>
#include <optional>
#include <string>

#include "base/result.hpp"
#include "runtime/emulator/pty_device.hpp"
#include "runtime/io/clock.hpp"

namespace seqc::emu {

struct PtyOptions {
  std::uint32_t baud = 0;           // set on the slave's termios when a standard rate (cosmetic)
  std::optional<std::string> link;  // symlink to create to the slave (an old symlink is replaced)
};

class PtyServer {
 public:
  enum class Stopped { Requested, HangUp };

  static Result<PtyServer> open(const PtyOptions& options);
  PtyServer(PtyServer&& other) noexcept;
  PtyServer& operator=(PtyServer&&) = delete;
  PtyServer(const PtyServer&) = delete;
  ~PtyServer();  // closes the pty and removes the symlink it made

  const std::string& slave_path() const { return slave_path_; }

  // The device's times are the clock's since serve() began, plus `resume` (a device served
  // again after a hang-up continues its own timeline).
  Result<Stopped> serve(PtyDevice& device, io::Clock& clock, const std::atomic<bool>& stop,
                        io::Duration resume = io::Duration{0});

 private:
  PtyServer() = default;
  void close_fds();

  int master_ = -1;
  int slave_ = -1;
  std::string slave_path_;
  std::optional<std::string> link_;
};

}  // namespace seqc::emu
