// What the in-process transport (emu:xarm, emu:lsc6) and the pseudo-terminal server drive: an
// emulated servo controller that takes bytes at the times they reach it and hands back the
// bytes it sends, in EMULATED time. XArmEmulator and Lsc6Emulator implement it; neither reads
// a clock.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "base/bytes.hpp"
#include "runtime/io/clock.hpp"

namespace seqc::emu {

// Why a controller dropped a whole frame on purpose (None: it was taken, or it was never a
// frame). The --record CSV writes each drop with its reason, so a record shows every frame the
// host sent that had no effect.
enum class DropReason : std::uint8_t {
  None,
  Busy,          // arrived while the controller was busy (or its one-frame buffer was full)
  FaultDrop,     // lost on the line (fault `drop`)
  FaultCorrupt,  // a framing byte corrupted (fault `corrupt`): the controller ignored it
  FaultSilent,   // after the controller fell silent (fault `silent-after`)
  FaultHangUp,   // the frame that hung up the link (fault `hangup-at`)
  FaultReset,    // taken by a power dip (faults `reset`, `reset-at`)
};

// "busy", "fault-drop", "fault-corrupt", "fault-silent", "fault-hangup", "fault-reset"; "" for
// None.
constexpr std::string_view drop_reason_name(DropReason reason) {
  switch (reason) {
    case DropReason::None:
      return "";
    case DropReason::Busy:
      return "busy";
    case DropReason::FaultDrop:
      return "fault-drop";
    case DropReason::FaultCorrupt:
      return "fault-corrupt";
    case DropReason::FaultSilent:
      return "fault-silent";
    case DropReason::FaultHangUp:
      return "fault-hangup";
    case DropReason::FaultReset:
      return "fault-reset";
  }
  return "";
}

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
