// Internal to the protocol library: little-endian field writer and reader for the servo
// controller's frame data and the checks encoding and decoding share, used by
// lsc_messages.cpp, lsc_decode.cpp, group_download.cpp and lsc6_messages.cpp.
#pragma once

#include <cstdint>
#include <string>
#include <utility>

#include "protocol/lsc/lsc_frame.hpp"
#include "protocol/lsc/lsc_messages.hpp"
#include "base/result.hpp"

namespace seqc::lsc::detail {

class FieldWriter {
 public:
  explicit FieldWriter(std::uint8_t cmd) { frame_.cmd = cmd; }
  FieldWriter& u8(std::uint8_t v) {
    frame_.data.push_back(v);
    return *this;
  }
  FieldWriter& u16(std::uint16_t v) {
    frame_.data.push_back(static_cast<std::uint8_t>(v & 0xff));
    frame_.data.push_back(static_cast<std::uint8_t>(v >> 8));
    return *this;
  }
  FieldWriter& i16(std::int16_t v) { return u16(static_cast<std::uint16_t>(v)); }
  FieldWriter& i8(std::int8_t v) { return u8(static_cast<std::uint8_t>(v)); }
  // The frame, or an error naming `what` if its data does not fit in one frame.
  Result<Frame> finish(const std::string& what) {
    if (frame_.data.size() > kMaxData) {
      return make_error(what + ": " + std::to_string(frame_.data.size()) +
                        " data bytes do not fit in one frame (at most " + std::to_string(kMaxData) +
                        ")");
    }
    return std::move(frame_);
  }

 private:
  Frame frame_;
};

// Reads fields in order; callers check sizes first (expect_size), so reads never run past
// the end (a short read returns 0 and marks the reader failed, as a second line of defence).
class FieldReader {
 public:
  explicit FieldReader(const Bytes& data) : data_(data) {}
  std::size_t remaining() const { return data_.size() - pos_; }
  std::uint8_t u8() {
    if (pos_ >= data_.size()) {
      failed_ = true;
      return 0;
    }
    return data_[pos_++];
  }
  std::uint16_t u16() {
    const std::uint8_t lo = u8();
    const std::uint8_t hi = u8();
    return static_cast<std::uint16_t>(lo | (hi << 8));
  }
  std::int16_t i16() { return static_cast<std::int16_t>(u16()); }
  std::int8_t i8() { return static_cast<std::int8_t>(u8()); }
  bool failed() const { return failed_; }

 private:
  const Bytes& data_;
  std::size_t pos_ = 0;
  bool failed_ = false;
};

// Error unless `data` has exactly `expected` bytes.
inline Status expect_size(const Bytes& data, std::size_t expected, const std::string& what) {
  if (data.size() != expected) {
    return make_error(what + ": expected " + std::to_string(expected) + " data bytes, got " +
                      std::to_string(data.size()));
  }
  return Ok{};
}

constexpr std::uint8_t cmd_of(Command c) { return static_cast<std::uint8_t>(c); }

// BusServoLimits' two flag fields hold only the values the document gives them.
inline Status check_limits(const BusServoLimits& l, const std::string& what) {
  if (l.led_status > 1) {
    return make_error(what + ": led_status " + std::to_string(l.led_status) +
                      " is outside 0..1 (0 = enable, 1 = disable)");
  }
  if ((l.led_warning & ~0x07) != 0) {
    return make_error(what + ": led_warning " + std::to_string(l.led_warning) +
                      " sets bits other than 0-2 (overheat, overvoltage, overposition)");
  }
  return Ok{};
}

}  // namespace seqc::lsc::detail
