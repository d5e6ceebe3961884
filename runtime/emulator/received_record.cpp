#include "runtime/emulator/received_record.hpp"

#include <chrono>

#include "protocol/lsc/lsc_messages.hpp"
#include "protocol/lsc6/lsc6_messages.hpp"
#include "runtime/io/time_text.hpp"

namespace seqc::emu {
namespace {

std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + "\"";
}

std::string status_of(DropReason dropped, bool framed) {
  if (dropped != DropReason::None) return "dropped:" + std::string(drop_reason_name(dropped));
  return framed ? "ok" : "unframed";
}

std::string line(io::TimePoint at, const std::string& status, const Bytes& raw,
                 const std::string& message) {
  return io::stamp_text(at) + "," + status + "," + to_hex(raw) + "," + csv_field(message) + "\n";
}

constexpr const char* kHeader = "time_s,status,bytes,message\n";

}  // namespace

std::string xarm_record_csv(const XArmEmulator& emu) {
  std::string out = kHeader;
  for (const ReceivedFrame& r : emu.received()) {
    // A frame dropped by a fault was never handed to the parser (r.frame is unset), but the
    // bytes may still be a whole frame worth naming.
    std::optional<lsc::Frame> frame = r.frame;
    if (!frame && r.dropped != DropReason::None) {
      if (auto f = lsc::decode_serial(r.raw)) frame = std::move(*f);
    }
    std::string message;
    if (frame) {
      auto request = lsc::decode_request(*frame);
      message = request ? lsc::describe(*request) : request.error().message;
    }
    if (r.flipped_at) {
      message += " (byte " + std::to_string(*r.flipped_at) + " flipped by the corrupt fault)";
    }
    const bool framed = r.frame.has_value() || r.dropped != DropReason::None;
    out += line(r.at, status_of(r.dropped, framed), r.raw, message);
  }
  return out;
}

std::string lsc6_record_csv(const Lsc6Emulator& emu) {
  std::string out = kHeader;
  for (const Lsc6Received& r : emu.received()) {
    std::string message;
    if (auto frame = lsc::decode_serial(r.raw)) {
      auto request = lsc6::decode_request(*frame);
      message = request ? lsc6::describe(*request) : "ignored: " + request.error().message;
    }
    out += line(r.at, status_of(r.dropped, true), r.raw, message);
  }
  return out;
}

}  // namespace seqc::emu
