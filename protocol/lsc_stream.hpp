// Streaming frame decoder for the servo controller's serial bytes.
#pragma once

#include <cstddef>
#include <deque>
#include <optional>

#include "base/bytes.hpp"
#include "protocol/lsc/lsc_frame.hpp"

namespace seqc::lsc {

// Takes bytes in any chunking and yields whole frames. Garbage before a header is skipped;
// a frame whose LEN is impossible (below 2, or above max_len) is rejected and the decoder
// resynchronises on the next 55 55 after the rejected header's first byte. In 55 55 55 the
// header starts at the second 55, so a frame whose LEN is 0x55 cannot be received (a reading,
// see lsc_stream.cpp). Never reads out of bounds and holds at most one frame's worth of
// pending bytes plus what feed() was given.
class FrameDecoder {
 public:
  explicit FrameDecoder(std::size_t max_len = 255);

  void feed(ByteView bytes);
  // The next complete frame, if one is buffered.
  std::optional<Frame> next();
  // Drops everything buffered (e.g. after a timeout, before a retry).
  void reset();

  // Bytes dropped while resynchronising, since construction.
  std::size_t skipped_bytes() const { return skipped_; }
  // Bytes held that do not yet form a frame.
  std::size_t pending_bytes() const { return buf_.size(); }

 private:
  std::size_t max_len_;
  std::deque<std::uint8_t> buf_;
  std::size_t skipped_ = 0;
};

}  // namespace seqc::lsc
