// A Transport decorator that writes every byte both ways to a text stream, with the time on
// the link's monotonic clock since the trace began (docs/trace.md):
//
//   t=0.000000 > 55 55 02 0f          bytes written to the device
//   t=0.012345 < 55 55 04 0f 4c 1d    bytes read from the device, as the read returned them
//   t=0.500000 < hang-up              the device went away
//   t=0.500000 # discarded pending input
//
// A hardware owner runs `seqc upload FILE --trace FILE` and sends the file back: it shows
// what the real controller answered, byte for byte, so a reading of the protocol can be
// corrected from it. Timeouts are not written (they are the absence of bytes).
#pragma once

#include <iosfwd>
#include <string>

#include "protocol/dialects.hpp"
#include "runtime/io/clock.hpp"
#include "runtime/io/transport.hpp"

namespace seqc::upload {

class TraceTransport final : public io::Transport {
 public:
  // `inner`, `clock` and `out` must outlive the decorator. Writes a header line naming the
  // device first and, when `dialect` is given, a line naming its row of the dialect table
  // ("# dialect: LSC-6", protocol/dialects.hpp), from which `seqc decode` reads the frames (an
  // LSC-6 session without a download looks like the xArm dialect's frames, and the Raspblock's
  // packets are no frames at all).
  TraceTransport(io::Transport& inner, io::Clock& clock, std::ostream& out,
                 const Dialect* dialect = nullptr);

  Status write(ByteView bytes) override;
  io::ReadResult read(std::span<std::uint8_t> buffer, io::TimePoint deadline) override;
  void discard_input() override;
  std::string describe() const override { return inner_.describe(); }
  double seconds_per_byte() const override { return inner_.seconds_per_byte(); }
  // The rest of the device's behaviour passes through unchanged, so a traced command paces,
  // drains and reconnects exactly as an untraced one.
  io::Duration frame_interval() const override { return inner_.frame_interval(); }
  std::size_t max_frame_bytes() const override { return inner_.max_frame_bytes(); }
  Status drain() override { return inner_.drain(); }
  bool reopen(io::TimePoint deadline) override;

 private:
  void line(char direction, const std::string& text);

  io::Transport& inner_;
  io::Clock& clock_;
  std::ostream& out_;
  io::TimePoint start_;
};

}  // namespace seqc::upload
