#include "protocol/lsc/lsc_stream.hpp"

#include <algorithm>

namespace seqc::lsc {

namespace {

// reading: in 55 55 55 the header is taken to start at the second 55 (a stray 55 before a
// real frame), not as LEN 0x55. Otherwise one stray 55 would hold back the next 85 bytes and
// swallow the frames in them. The price: a frame with LEN 0x55 (83 data bytes) cannot be
// received; no message the controller or the project sends is that long in practice (it
// would take 41 offsets or 82 servo ids in one frame). A capture of the controller receiving
// 55 55 55 04 ... would show which way its own receiver reads it.
bool is_header_byte_not_len(std::size_t len) { return len == kHeaderByte; }

}  // namespace

FrameDecoder::FrameDecoder(std::size_t max_len) : max_len_(std::min<std::size_t>(max_len, 255)) {}

void FrameDecoder::feed(ByteView bytes) { buf_.insert(buf_.end(), bytes.begin(), bytes.end()); }

void FrameDecoder::reset() { buf_.clear(); }

std::optional<Frame> FrameDecoder::next() {
  // Every rejection drops only the first byte and rescans, so a real header that starts
  // inside a rejected one (a stray 55 before 55 55, or a bad LEN) is still found.
  auto drop_one = [this] {
    buf_.pop_front();
    ++skipped_;
  };
  while (!buf_.empty()) {
    if (buf_[0] != kHeaderByte) {
      drop_one();
      continue;
    }
    if (buf_.size() < 2) return std::nullopt;
    if (buf_[1] != kHeaderByte) {
      drop_one();
      continue;
    }
    if (buf_.size() < 3) return std::nullopt;
    const std::size_t len = buf_[2];
    if (is_header_byte_not_len(len) || len < kMinLen || len > max_len_) {
      drop_one();
      continue;
    }
    const std::size_t total = len + 2;
    if (buf_.size() < total) return std::nullopt;
    Frame frame;
    frame.cmd = buf_[3];
    frame.data.assign(buf_.begin() + static_cast<long>(kHeaderSize),
                      buf_.begin() + static_cast<long>(total));
    buf_.erase(buf_.begin(), buf_.begin() + static_cast<long>(total));
    return frame;
  }
  return std::nullopt;
}

}  // namespace seqc::lsc
