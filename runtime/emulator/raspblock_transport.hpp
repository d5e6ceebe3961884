// The Raspblock emulator as a byte link (emu:raspblock): every write is handed to the emulator
// at the clock's time since the transport was made. The board never replies, so a read only
// waits for its deadline and times out, like the real one.
#pragma once

#include <span>
#include <string>

#include "runtime/emulator/raspblock_emulator.hpp"
#include "runtime/io/clock.hpp"
#include "runtime/io/transport.hpp"

namespace seqc::emu {

class RaspblockTransport final : public io::Transport {
 public:
  // `board` and `clock` must outlive the transport.
  RaspblockTransport(RaspblockEmulator& board, io::Clock& clock);
  Status write(ByteView bytes) override;
  io::ReadResult read(std::span<std::uint8_t> buffer, io::TimePoint deadline) override;
  void discard_input() override {}
  std::string describe() const override { return "emu:raspblock"; }

 private:
  RaspblockEmulator& board_;
  io::Clock& clock_;
  io::TimePoint origin_;
};

}  // namespace seqc::emu
