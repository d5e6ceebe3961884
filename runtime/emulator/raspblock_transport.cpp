#include "runtime/emulator/raspblock_transport.hpp"

namespace seqc::emu {

RaspblockTransport::RaspblockTransport(RaspblockEmulator& board, io::Clock& clock)
    : board_(board), clock_(clock), origin_(clock.now()) {}

Status RaspblockTransport::write(ByteView bytes) {
  board_.receive(bytes, clock_.now() - origin_);
  return Ok{};
}

io::ReadResult RaspblockTransport::read(std::span<std::uint8_t>, io::TimePoint deadline) {
  clock_.sleep_until(deadline);
  return {io::ReadStatus::Timeout, 0, {}};
}

}  // namespace seqc::emu
