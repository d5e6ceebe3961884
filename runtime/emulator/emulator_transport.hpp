// io::Transport over an in-process XArmEmulator sharing a ManualClock ("emu:xarm"), so the
// uploader's real code runs against the emulated controller in emulated time.
//   write()  paces by the emulator's baud on the clock (10 bits per byte, if baud > 0), then
//            delivers the bytes at the new time. Fails once the link has hung up.
//   read()   returns output already due; otherwise advances the clock to the next output
//            byte if that comes by the deadline, else to the deadline -> Timeout. A hung-up
//            link -> HangUp.
#pragma once

#include <string>

#include "runtime/emulator/xarm_emulator.hpp"
#include "runtime/io/clock.hpp"
#include "runtime/io/transport.hpp"

namespace seqc::emu {

class EmulatorTransport final : public io::Transport {
 public:
  EmulatorTransport(XArmEmulator& emulator, io::ManualClock& clock);

  Status write(ByteView bytes) override;
  io::ReadResult read(std::span<std::uint8_t> buffer, io::TimePoint deadline) override;
  void discard_input() override;
  std::string describe() const override { return "emu:xarm"; }
  double seconds_per_byte() const override;

 private:
  io::ReadResult deliver(std::span<std::uint8_t> buffer);

  XArmEmulator& emu_;
  io::ManualClock& clock_;
  Bytes inbox_;  // output taken from the emulator but not yet read
};

}  // namespace seqc::emu
