// What the pseudo-terminal server drives: a byte-level device in emulated time, and adapters
// for the two emulators.
//
// The server stamps the bytes it reads from the pty with the time it read them and calls
// receive(); it calls take_output(now) whenever it wakes and writes what comes back. It
// sleeps until next_output_at(), which is when the device next has something to do: usually
// the next output byte, but possibly earlier (a lower bound), e.g. when a received byte is
// due to reach the emulated controller. Waking early is harmless; waking late only delays
// the output in real time, never in emulated time.
#pragma once

#include <cstddef>
#include <optional>
#include <ostream>
#include <vector>

#include "base/bytes.hpp"
#include "runtime/emulator/controller_device.hpp"
#include "runtime/emulator/raspblock_emulator.hpp"
#include "runtime/emulator/serial_line.hpp"
#include "runtime/emulator/xarm_emulator.hpp"
#include "runtime/io/clock.hpp"

namespace seqc::emu {

class PtyDevice {
 public:
  virtual ~PtyDevice() = default;
  virtual void receive(ByteView bytes, io::TimePoint at) = 0;
  virtual std::optional<io::TimePoint> next_output_at() const = 0;
  virtual Bytes take_output(io::TimePoint upto) = 0;
  virtual bool hung_up() const = 0;
};

// A servo controller (xArm or LSC-6 firmware) behind a pty. A pty has no line rate: whatever the
// host writes is readable at once. The device puts the host's bytes on an InputLine at the
// emulator's baud, so each byte reaches the controller after its wire time (byte k of a write at t
// at t + (k+1) x 10 bits / baud, queued behind bytes still on the line) and a frame is processed
// only once its last byte has arrived, as on a real UART. Every byte is handed to the
// emulator stamped with its own delivery time, however late the server wakes, so the
// emulated timeline depends only on when the host wrote.
//
// Wake-ups (next_output_at) are kept to the moments that matter, not one per byte: when a
// queued byte completes a frame (found by cutting the queued bytes with a RequestFramer of
// the device's own, exactly as the controller will), when the last queued byte arrives, and
// when the last byte of the next reply is due. Output is handed over a message at a time: no
// byte earlier than its due time, the message when its last byte is due (as a USB adapter
// usually hands a short reply to the host in one piece). Real adapters sometimes flush part of
// a reply when their latency timer runs out, so the host must take replies split across
// reads: the emulator's `split` fault queues a reply as two messages, which this device hands
// over in two writes.
class ControllerPtyDevice final : public PtyDevice {
 public:
  explicit ControllerPtyDevice(ControllerDevice& emu);
  void receive(ByteView bytes, io::TimePoint at) override;
  std::optional<io::TimePoint> next_output_at() const override;
  Bytes take_output(io::TimePoint upto) override;
  bool hung_up() const override { return emu_.hung_up(); }

  // Bytes written by the host that have not reached the controller yet.
  bool input_pending() const { return !input_.empty(); }
  // The host reaches the device again after a hang-up (ControllerDevice::reconnect); bytes that
  // were on their way are lost. False if the device is not back by `at`.
  bool reconnect(io::TimePoint at);

 private:
  void deliver(io::TimePoint upto);

  ControllerDevice& emu_;
  InputLine input_;
  RequestFramer framer_;                       // the controller's cut of the queued bytes
  std::vector<io::TimePoint> frame_ends_;      // arrival of queued bytes that complete a frame
  std::optional<io::TimePoint> last_arrival_;  // of the last byte queued
};

// Prints each new timeline entry (describe_change) on `log`, if given, as it happens.
class RaspblockPtyDevice final : public PtyDevice {
 public:
  RaspblockPtyDevice(RaspblockEmulator& emu, std::ostream* log) : emu_(emu), log_(log) {}
  void receive(ByteView bytes, io::TimePoint at) override;
  std::optional<io::TimePoint> next_output_at() const override { return std::nullopt; }
  Bytes take_output(io::TimePoint) override { return {}; }
  bool hung_up() const override { return false; }

 private:
  RaspblockEmulator& emu_;
  std::ostream* log_;
  std::size_t printed_ = 0;
  std::size_t rejections_printed_ = 0;
};

}  // namespace seqc::emu
