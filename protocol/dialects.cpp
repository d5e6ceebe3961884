#include "protocol/dialects.hpp"

#include <utility>

#include "protocol/lsc/lsc_frame.hpp"
#include "protocol/lsc/lsc_messages.hpp"
#include "protocol/lsc/lsc_stream.hpp"
#include "protocol/lsc6/lsc6_messages.hpp"
#include "protocol/raspblock/raspblock.hpp"

namespace seqc {
namespace {

// ---- 55 55 LEN CMD DATA frames (both servo-controller dialects) ----------------------------

Result<Bytes> encode_frame(const Unit& unit) {
  return lsc::encode_serial(lsc::Frame{unit.command, unit.data});
}

Result<Unit> decode_frame(ByteView bytes) {
  auto frame = lsc::decode_serial(bytes);
  if (!frame) return frame.error();
  return Unit{frame->cmd, std::move(frame->data)};
}

// Whether any whole frame in `bytes` has command `cmd`; `any` is set when there is a frame at all.
bool has_frame_with(ByteView bytes, std::uint8_t cmd, bool& any) {
  lsc::FrameDecoder frames;
  frames.feed(bytes);
  any = false;
  while (auto f = frames.next()) {
    any = true;
    if (f->cmd == cmd) return true;
  }
  return false;
}

// The LSC-6's DownloadAction: the xArm dialect has no command 25, and every LSC-6 session that
// stores a group sends it.
constexpr std::uint8_t kLsc6Download = static_cast<std::uint8_t>(lsc6::Command::DownloadAction);

template <class Message>
Result<std::string> described(Result<Message> message) {
  if (!message) return message.error();
  return describe(*message);
}

// ---- xArm / LSC-16 / LSC-32 ------------------------------------------------------------------

// The questions that tell the two servo-controller dialects apart (docs/protocol/lsc-6.md):
// each dialect's trace may hold the other's question and, from a board of the other dialect,
// its answer. They are named, not flagged.
Result<std::string> lsc6_question(const Unit& u) {
  auto a = lsc6::decode_request(lsc::Frame{u.command, u.data});
  if (!a) return a.error();
  return describe(*a) + " (the LSC-6 question: no command of this dialect)";
}
Result<std::string> xarm_question(const Unit& u) {
  auto q = lsc::decode_request(lsc::Frame{u.command, u.data});
  if (!q) return q.error();
  return describe(*q) + " (the xArm question: the LSC-6 ignores it)";
}

Result<std::string> xarm_request(const Unit& u) {
  // Only the question itself (total 1, index 255, no servos, time 0): a real LSC-6 download
  // frame in an xArm trace is still no request of this dialect.
  if (u.command == kLsc6Download && u.data.size() == 6 && u.data[1] == 1 && u.data[2] == 255 &&
      u.data[3] == 0) {
    return lsc6_question(u);
  }
  return described(lsc::decode_request(lsc::Frame{u.command, u.data}));
}
Result<std::string> xarm_reply(const Unit& u) {
  if (u.command == kLsc6Download && u.data.empty()) {
    auto a = lsc6::decode_reply(lsc::Frame{u.command, u.data});
    if (!a) return a.error();
    return describe(*a) + " (an LSC-6 answering the LSC-6 question)";
  }
  return described(lsc::decode_reply(lsc::Frame{u.command, u.data}));
}
// Frames, none of them the LSC-6's download.
bool xarm_sniff(ByteView bytes) {
  bool any = false;
  return !has_frame_with(bytes, kLsc6Download, any) && any;
}

// ---- LSC-6 / LeArm -----------------------------------------------------------------------------

Result<std::string> lsc6_request(const Unit& u) {
  const auto battery = static_cast<std::uint8_t>(lsc::Command::GetBatteryVoltage);
  if (u.command == battery && u.data.empty()) return xarm_question(u);
  return described(lsc6::decode_request(lsc::Frame{u.command, u.data}));
}
Result<std::string> lsc6_reply(const Unit& u) {
  const auto battery = static_cast<std::uint8_t>(lsc::Command::GetBatteryVoltage);
  if (u.command == battery && u.data.size() == 2) {
    auto v = lsc::decode_reply(lsc::Frame{u.command, u.data});
    if (!v) return v.error();
    return describe(*v) + " (a board of the xArm dialect answering the xArm question)";
  }
  return described(lsc6::decode_reply(lsc::Frame{u.command, u.data}));
}
// A frame of its download. A session without one (moves, runs, the erase) is frames the xArm
// dialect has as well, so it cannot be told apart from the bytes.
bool lsc6_sniff(ByteView bytes) {
  bool any = false;
  return has_frame_with(bytes, kLsc6Download, any);
}

// ---- Raspblock -------------------------------------------------------------------------------

constexpr std::size_t kPacketOverhead = 5;  // FF FE FUNC LEN ... CHK

std::uint8_t packet_checksum(std::uint8_t func, ByteView data) {
  unsigned sum = func + static_cast<unsigned>(data.size());
  for (std::uint8_t b : data) sum += b;
  return static_cast<std::uint8_t>(sum & 0xff);
}

Result<Bytes> encode_packet(const Unit& unit) {
  if (unit.data.size() > 0xff) return make_error("a Raspblock packet carries at most 255 bytes");
  Bytes out{raspblock::kHeader0, raspblock::kHeader1, unit.command,
            static_cast<std::uint8_t>(unit.data.size())};
  out.insert(out.end(), unit.data.begin(), unit.data.end());
  out.push_back(packet_checksum(unit.command, unit.data));
  return out;
}

Result<Unit> decode_packet(ByteView bytes) {
  if (bytes.size() < kPacketOverhead || bytes[0] != raspblock::kHeader0 ||
      bytes[1] != raspblock::kHeader1) {
    return make_error("not a Raspblock packet (FF FE FUNC LEN DATA CHK)");
  }
  if (bytes.size() != kPacketOverhead + bytes[3]) {
    return make_error("the packet's LEN does not match its length");
  }
  Unit unit{bytes[2], Bytes(bytes.begin() + 4, bytes.end() - 1)};
  if (bytes.back() != packet_checksum(unit.command, unit.data)) {
    return make_error("bad checksum");
  }
  return unit;
}

Result<std::string> raspblock_request(const Unit& u) {
  auto bytes = encode_packet(u);
  if (!bytes) return bytes.error();
  auto packet = raspblock::decode(*bytes);
  if (!packet) return packet.error();
  return raspblock::describe(*packet);
}
bool raspblock_sniff(ByteView bytes) { return framing_of(bytes) == Framing::Packets; }

constexpr const Dialect* kDialects[] = {&kXarmDialect, &kLsc6Dialect, &kRaspblockDialect};

}  // namespace

const Dialect kXarmDialect = {
    .key = "xarm",
    .name = "xArm / LSC-16 / LSC-32",
    .decode_name = "hex",
    .framing = Framing::Frames,
    .encode = encode_frame,
    .decode = decode_frame,
    .describe_request = xarm_request,
    .describe_reply = xarm_reply,
    .sniff = xarm_sniff,
};

const Dialect kLsc6Dialect = {
    .key = "lsc6",
    .name = "LSC-6",
    .decode_name = "lsc6",
    .framing = Framing::Frames,
    .encode = encode_frame,
    .decode = decode_frame,
    .describe_request = lsc6_request,
    .describe_reply = lsc6_reply,
    .sniff = lsc6_sniff,
};

const Dialect kRaspblockDialect = {
    .key = "raspblock",
    .name = "Raspblock",
    .decode_name = "raspblock",
    .framing = Framing::Packets,
    .encode = encode_packet,
    .decode = decode_packet,
    .describe_request = raspblock_request,
    .describe_reply = nullptr,
    .sniff = raspblock_sniff,
};

std::span<const Dialect* const> all_dialects() { return kDialects; }

const Dialect* find_dialect(std::string_view key) {
  for (const Dialect* d : kDialects) {
    if (d->key == key) return d;
  }
  return nullptr;
}

const Dialect* dialect_named(std::string_view name) {
  for (const Dialect* d : kDialects) {
    if (d->name == name) return d;
  }
  return nullptr;
}

const Dialect* dialect_decoded_as(std::string_view decode_name) {
  for (const Dialect* d : kDialects) {
    if (d->decode_name == decode_name) return d;
  }
  return nullptr;
}

Framing framing_of(ByteView bytes) {
  return bytes.size() >= 2 && bytes[0] == raspblock::kHeader0 && bytes[1] == raspblock::kHeader1
             ? Framing::Packets
             : Framing::Frames;
}

const Dialect& sniff_dialect(ByteView bytes, Framing framing) {
  const Dialect* first = nullptr;
  for (const Dialect* d : kDialects) {
    if (d->framing != framing) continue;
    if (first == nullptr) first = d;
    if (d->sniff(bytes)) return *d;
  }
  return *first;
}

const Dialect& sniff_dialect(ByteView bytes) { return sniff_dialect(bytes, framing_of(bytes)); }

}  // namespace seqc
