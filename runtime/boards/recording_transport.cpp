#include "runtime/boards/recording_transport.hpp"

#include <algorithm>

namespace seqc::boards {

AcknowledgingTransport::AcknowledgingTransport(io::ManualClock& clock, Acknowledge acknowledge)
    : clock_(clock), acknowledge_(acknowledge) {}

Status AcknowledgingTransport::write(ByteView bytes) {
  writes_.emplace_back(bytes.begin(), bytes.end());
  const Bytes reply = acknowledge_(bytes);
  pending_.insert(pending_.end(), reply.begin(), reply.end());
  return Ok{};
}

io::ReadResult AcknowledgingTransport::read(std::span<std::uint8_t> buffer,
                                            io::TimePoint deadline) {
  if (pending_.empty()) {
    clock_.sleep_until(deadline);
    return {io::ReadStatus::Timeout, 0, {}};
  }
  const std::size_t n = std::min(buffer.size(), pending_.size());
  std::copy_n(pending_.begin(), n, buffer.begin());
  pending_.erase(pending_.begin(), pending_.begin() + static_cast<std::ptrdiff_t>(n));
  return {io::ReadStatus::Data, n, {}};
}

void AcknowledgingTransport::discard_input() { pending_.clear(); }

}  // namespace seqc::boards
