// A byte link to a device: serial port, pseudo-terminal, USB HID, or the in-process emulator.
// Reads take an absolute deadline on the Clock the transport was built with, so a fake clock
// makes every timeout instant and deterministic.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

#include "runtime/io/clock.hpp"
#include "base/bytes.hpp"
#include "base/result.hpp"

namespace seqc::io {

enum class ReadStatus {
  Data,     // count > 0 bytes were read
  Timeout,  // the deadline passed with nothing to read
  HangUp,   // the device went away (unplugged, pty closed): not a timeout
  Error,    // any other failure; see message
};

struct ReadResult {
  ReadStatus status = ReadStatus::Timeout;
  std::size_t count = 0;
  std::string message;
};

class Transport {
 public:
  virtual ~Transport() = default;

  // Writes all bytes or fails. Frame-oriented transports (HID) require exactly one whole
  // frame per call.
  virtual Status write(ByteView bytes) = 0;
  // Reads what is available, waiting until `deadline` for at least one byte.
  virtual ReadResult read(std::span<std::uint8_t> buffer, TimePoint deadline) = 0;
  // Drops input that arrived before now (stale replies, notifications).
  virtual void discard_input() = 0;
  // For messages: "/dev/ttyUSB0 at 9600 baud", "emu:xarm", "hid:0483:5750 LOBOT".
  virtual std::string describe() const = 0;
  // Seconds per byte on the wire (10 bits / baud), or 0 where unknown (HID, unpaced emulator).
  virtual double seconds_per_byte() const { return 0.0; }
  // The shortest time between two frames the link can carry whatever their size (HID: one
  // report per polling interval), or 0 where there is no such floor.
  virtual Duration frame_interval() const { return Duration{0}; }
  // The largest frame one write can carry (HID: what fits one report), or 0 for no limit.
  virtual std::size_t max_frame_bytes() const { return 0; }
  // Waits until every byte written so far has left the host (tcdrain on a serial port). The
  // default has nothing to wait for: its write() returns once the bytes are gone.
  virtual Status drain() { return Ok{}; }
  // After a HangUp: waits until `deadline` for the same device to come back (a cable that
  // slipped, a board that re-enumerated) and reconnects to it, with the same settings. True
  // when the link works again. The default cannot reconnect.
  virtual bool reopen(TimePoint /*deadline*/) { return false; }
};

}  // namespace seqc::io
