#include "protocol/lsc/lsc_frame.hpp"

#include <algorithm>
#include <string>

namespace seqc::lsc {

namespace {

std::size_t serial_size(const Frame& frame) { return kHeaderSize + frame.data.size(); }

Bytes serial_bytes(const Frame& frame) {
  Bytes out;
  out.reserve(serial_size(frame));
  out.push_back(kHeaderByte);
  out.push_back(kHeaderByte);
  out.push_back(static_cast<std::uint8_t>(frame.data.size() + kMinLen));
  out.push_back(frame.cmd);
  out.insert(out.end(), frame.data.begin(), frame.data.end());
  return out;
}

// Checks the header at the start of `bytes` and returns LEN.
Result<std::size_t> header_len(ByteView bytes, const char* what) {
  if (bytes.size() < kHeaderSize) {
    return make_error(std::string(what) + ": " + std::to_string(bytes.size()) +
                      " bytes is shorter than the 4-byte header 55 55 LEN CMD");
  }
  if (bytes[0] != kHeaderByte || bytes[1] != kHeaderByte) {
    return make_error(std::string(what) + ": does not start with 55 55 (starts with " +
                      to_hex(bytes.first(2)) + ")");
  }
  const std::size_t len = bytes[2];
  if (len < kMinLen) {
    return make_error(std::string(what) + ": LEN " + std::to_string(len) +
                      " is below 2 (LEN counts itself and CMD)");
  }
  return len;
}

Frame frame_from(ByteView bytes, std::size_t len) {
  Frame frame;
  frame.cmd = bytes[3];
  frame.data.assign(bytes.begin() + kHeaderSize, bytes.begin() + static_cast<long>(len + 2));
  return frame;
}

}  // namespace

Result<Bytes> encode_serial(const Frame& frame) {
  if (frame.data.size() > kMaxData) {
    return make_error("frame data of " + std::to_string(frame.data.size()) +
                      " bytes does not fit in one frame (at most " + std::to_string(kMaxData) +
                      ")");
  }
  return serial_bytes(frame);
}

Result<Frame> decode_serial(ByteView bytes) {
  auto len = header_len(bytes, "serial frame");
  if (!len) return len.error();
  if (bytes.size() != *len + 2) {
    return make_error("serial frame: LEN " + std::to_string(*len) + " means " +
                      std::to_string(*len + 2) + " bytes, got " + std::to_string(bytes.size()));
  }
  return frame_from(bytes, *len);
}

Result<Bytes> encode_hid_report(const Frame& frame) {
  if (frame.data.size() > kHidMaxData) {
    return make_error("frame data of " + std::to_string(frame.data.size()) +
                      " bytes does not fit in one 64-byte HID report (at most " +
                      std::to_string(kHidMaxData) + ")");
  }
  Bytes report(1 + kHidReportData, 0);  // report id 0, then zero padding
  const Bytes serial = serial_bytes(frame);
  std::copy(serial.begin(), serial.end(), report.begin() + 1);
  return report;
}

Result<Frame> decode_hid_report(ByteView report) {
  if (report.size() > kHidReportData) {
    return make_error("HID report of " + std::to_string(report.size()) +
                      " bytes is longer than 64");
  }
  auto len = header_len(report, "HID report");
  if (!len) return len.error();
  if (*len + 2 > report.size()) {
    return make_error("HID report: LEN " + std::to_string(*len) + " means " +
                      std::to_string(*len + 2) + " bytes, report has " +
                      std::to_string(report.size()));
  }
  return frame_from(report, *len);
}

}  // namespace seqc::lsc
