// The dry run's device. Every write is recorded as one frame and answered with what the board's
// row says accepts it, on its own ManualClock and unpaced (seconds_per_byte() == 0, so the
// uploader's early-ack check never holds a reply). It stands in for a board that accepts
// everything, so the real uploader runs against it and writes exactly what an upload sends.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "runtime/io/clock.hpp"
#include "runtime/io/transport.hpp"
#include "base/bytes.hpp"

namespace seqc::boards {

class AcknowledgingTransport final : public io::Transport {
 public:
  using Acknowledge = Bytes (*)(ByteView request);
  AcknowledgingTransport(io::ManualClock& clock, Acknowledge acknowledge);

  Status write(ByteView bytes) override;  // records; queues acknowledge(bytes)
  // Queued bytes, else clock.sleep_until(deadline) -> Timeout.
  io::ReadResult read(std::span<std::uint8_t> buffer, io::TimePoint deadline) override;
  void discard_input() override;  // drops queued replies
  std::string describe() const override { return "dry run"; }

  const std::vector<Bytes>& writes() const { return writes_; }

 private:
  io::ManualClock& clock_;
  Acknowledge acknowledge_;
  std::vector<Bytes> writes_;
  Bytes pending_;
};

}  // namespace seqc::boards
