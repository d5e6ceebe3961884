// io::Transport over an in-process emulated controller (XArmEmulator "emu:xarm", Lsc6Emulator
// "emu:lsc6") sharing a ManualClock, so the uploader's real code runs against it in emulated
// time.
//   write()  puts the bytes on the same receive line model as the pty server (InputLine at the
//            emulator's baud: byte k of a write at t arrives at t + (k+1) x 10 bits / baud),
//            advances the clock until the last of them has arrived, as if the host waited for
//            its bytes to drain, and hands each to the emulator at its own arrival time. Fails
//            once the link has hung up.
//   read()   returns output already due; otherwise advances the clock to the next output
//            byte if that comes by the deadline, else to the deadline -> Timeout. A hung-up
//            link -> HangUp.
//   reopen() waits (on the clock) until the emulated device is back after a hang-up, if it
//            comes back by the deadline (XArmFaults::back_after), and reconnects.
#pragma once

#include <string>

#include "runtime/emulator/controller_device.hpp"
#include "runtime/emulator/serial_line.hpp"
#include "runtime/io/clock.hpp"
#include "runtime/io/transport.hpp"

namespace seqc::emu {

class EmulatorTransport final : public io::Transport {
 public:
  EmulatorTransport(ControllerDevice& emulator, io::ManualClock& clock);

  Status write(ByteView bytes) override;
  io::ReadResult read(std::span<std::uint8_t> buffer, io::TimePoint deadline) override;
  void discard_input() override;
  std::string describe() const override { return emu_.port_name(); }
  double seconds_per_byte() const override;
  bool reopen(io::TimePoint deadline) override;

 private:
  io::ReadResult deliver(std::span<std::uint8_t> buffer);

  ControllerDevice& emu_;
  io::ManualClock& clock_;
  InputLine input_;  // the host's bytes on their way to the controller
  Bytes inbox_;      // output taken from the emulator but not yet read
};

}  // namespace seqc::emu
