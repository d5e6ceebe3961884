// What the in-process transport (emu:xarm, emu:lsc6) and the pseudo-terminal server drive: an
// emulated servo controller that takes bytes at the times they reach it and hands back the
// bytes it sends, in EMULATED time. XArmEmulator and Lsc6Emulator implement it; neither reads
// a clock.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "runtime/io/clock.hpp"
#include "runtime/protocol/bytes.hpp"

namespace seqc::emu {

class ControllerDevice {
 public:
  virtual ~ControllerDevice() = default;
  // Bytes reach the controller, all at `at` (after their wire time: see InputLine).
  virtual void receive(ByteView bytes, io::TimePoint at) = 0;
  // Runs emulated time up to `t`.
  virtual void advance_to(io::TimePoint t) = 0;
  // When the next output byte is due; may be a lower bound (advance and ask again).
  virtual std::optional<io::TimePoint> next_output_at() const = 0;
  // When the last byte of the next message out is due (same lower-bound rule).
  virtual std::optional<io::TimePoint> next_message_end_at() const = 0;
  // Advances to `upto` and returns the output bytes due at or before it.
  virtual Bytes take_output(io::TimePoint upto) = 0;
  virtual bool hung_up() const = 0;
  // When the device can be reached again after a hang-up; nullopt if it stays away.
  virtual std::optional<io::TimePoint> back_at() const = 0;
  virtual bool reconnect(io::TimePoint at) = 0;
  // The line rate both ways (0 = unpaced).
  virtual std::uint32_t baud() const = 0;
  // The receive parser's inter-byte gap that drops a partial frame (0 = none).
  virtual io::Duration frame_gap() const = 0;
  // How messages name it: "emu:xarm", "emu:lsc6".
  virtual std::string port_name() const = 0;
};

}  // namespace seqc::emu
