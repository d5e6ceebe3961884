// Servo controller (LewanSoul/Hiwonder xArm, LSC-16/32) frames: serial form and USB-HID form.
//
// Serial:  55 55 LEN CMD DATA...        LEN = len(DATA) + 2, no checksum.
// HID out: 00 55 55 LEN CMD DATA... 00*  report id 0, then the serial bytes padded to 64.
// HID in:  55 55 LEN CMD DATA... 00*     input reports start directly at the header.
// Multi-byte fields are little-endian (see lsc_messages.hpp).
#pragma once

#include <cstddef>
#include <cstdint>

#include "base/bytes.hpp"
#include "base/result.hpp"

namespace seqc::lsc {

inline constexpr std::uint8_t kHeaderByte = 0x55;
inline constexpr std::size_t kHeaderSize = 4;           // 55 55 LEN CMD
inline constexpr std::size_t kMinLen = 2;               // LEN counts itself and CMD
inline constexpr std::size_t kMaxData = 255 - kMinLen;  // LEN is one byte
inline constexpr std::size_t kHidReportData = 64;       // bytes after the report id
inline constexpr std::size_t kHidMaxData = kHidReportData - kHeaderSize;

struct Frame {
  std::uint8_t cmd = 0;
  Bytes data;
  friend bool operator==(const Frame&, const Frame&) = default;
};

// 55 55 LEN CMD DATA. Error if the data does not fit in one frame.
Result<Bytes> encode_serial(const Frame& frame);

// Decodes exactly one whole serial frame (no leading or trailing bytes).
Result<Frame> decode_serial(ByteView bytes);

// 65 bytes for hidapi's hid_write: report id 0, the serial frame, zero padding.
// Error if the frame does not fit in one 64-byte report.
Result<Bytes> encode_hid_report(const Frame& frame);

// Decodes one input report as hidapi returns it (starting at 55 55, padding ignored).
Result<Frame> decode_hid_report(ByteView report);

}  // namespace seqc::lsc
