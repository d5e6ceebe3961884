#include "protocol/fpp_multisync.hpp"

#include <algorithm>
#include <bit>
#include <cstring>

namespace seqc::fpp {
namespace {

constexpr std::size_t kSyncFixed = 10;  // action, file type, frame, seconds

// Offsets of a ping's fields in its extra data, and their sizes (the string's bytes and its NUL).
constexpr std::size_t kHostnameAt = 12, kHostnameField = 65;
constexpr std::size_t kVersionAt = 77, kVersionField = 41;
constexpr std::size_t kHardwareAt = 118, kHardwareField = 41;
constexpr std::size_t kRangesAt = 159, kRangesField = 121;

std::uint32_t read_u32_le(ByteView b, std::size_t at) {
  return static_cast<std::uint32_t>(b[at]) | static_cast<std::uint32_t>(b[at + 1]) << 8 |
         static_cast<std::uint32_t>(b[at + 2]) << 16 | static_cast<std::uint32_t>(b[at + 3]) << 24;
}

void put_u32_le(Bytes& out, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
}

// A NUL-terminated string within [at, at + field) of `extra`, cut where the data ends.
std::string field_text(ByteView extra, std::size_t at, std::size_t field) {
  if (at >= extra.size()) return {};
  const std::size_t end = std::min(extra.size(), at + field);
  std::string s;
  for (std::size_t i = at; i < end && extra[i] != 0; ++i) s.push_back(static_cast<char>(extra[i]));
  return s;
}

void put_field(Bytes& extra, std::size_t at, std::size_t field, const std::string& text) {
  const std::size_t n = std::min(text.size(), field - 1);  // the last byte stays NUL
  std::memcpy(extra.data() + at, text.data(), n);
}

Bytes header(PacketType type, std::size_t extra) {
  return {'F',
          'P',
          'P',
          'D',
          static_cast<std::uint8_t>(type),
          static_cast<std::uint8_t>(extra & 0xff),
          static_cast<std::uint8_t>(extra >> 8)};
}

Result<Packet> decode_sync(ByteView extra) {
  if (extra.size() < kSyncFixed + 1) {
    return make_error("sync packet: " + std::to_string(extra.size()) +
                      " bytes of data, fewer than the " + std::to_string(kSyncFixed + 1) +
                      " of an empty file name");
  }
  SyncPacket p;
  if (extra[0] > 3) return make_error("sync packet: unknown action " + std::to_string(extra[0]));
  if (extra[1] > 1) return make_error("sync packet: unknown file type " + std::to_string(extra[1]));
  p.action = static_cast<SyncAction>(extra[0]);
  p.file = static_cast<SyncFile>(extra[1]);
  p.frame = read_u32_le(extra, 2);
  p.seconds = std::bit_cast<float>(read_u32_le(extra, 6));
  const ByteView name = extra.subspan(kSyncFixed);
  const auto nul = std::find(name.begin(), name.end(), std::uint8_t{0});
  if (nul == name.end()) return make_error("sync packet: file name without its NUL");
  const auto length = static_cast<std::size_t>(nul - name.begin());
  if (length > kMaxFileName) {
    return make_error("sync packet: file name of " + std::to_string(length) +
                      " bytes, longer than " + std::to_string(kMaxFileName));
  }
  p.file_name.assign(name.begin(), nul);
  if (!(p.seconds >= 0) || p.seconds > 1e7f) {
    return make_error("sync packet: seconds elapsed out of range");
  }
  return Packet{std::move(p)};
}

Result<Packet> decode_ping(ByteView extra) {
  if (extra.size() < kPingV1Extra) {
    return make_error("ping packet: " + std::to_string(extra.size()) +
                      " bytes of data, fewer than the " + std::to_string(kPingV1Extra) +
                      " of the first version");
  }
  PingPacket p;
  p.version = extra[0];
  p.discover = extra[1] == 1;
  p.system_type = extra[2];
  p.major = static_cast<std::uint16_t>(extra[3] << 8 | extra[4]);
  p.minor = static_cast<std::uint16_t>(extra[5] << 8 | extra[6]);
  p.mode = extra[7];
  std::copy(extra.begin() + 8, extra.begin() + 12, p.address.begin());
  p.hostname = field_text(extra, kHostnameAt, kHostnameField);
  p.version_text = field_text(extra, kVersionAt, kVersionField);
  p.hardware = field_text(extra, kHardwareAt, kHardwareField);
  p.ranges = field_text(extra, kRangesAt, kRangesField);
  return Packet{std::move(p)};
}

}  // namespace

Result<Packet> decode(ByteView datagram) {
  if (datagram.size() > kMaxPacketBytes) {
    return make_error("packet of " + std::to_string(datagram.size()) + " bytes, longer than " +
                      std::to_string(kMaxPacketBytes));
  }
  if (datagram.size() < kHeaderBytes || datagram[0] != 'F' || datagram[1] != 'P' ||
      datagram[2] != 'P' || datagram[3] != 'D') {
    return make_error("not an FPP packet (no FPPD header)");
  }
  const std::size_t extra = static_cast<std::size_t>(datagram[5]) | datagram[6] << 8;
  const std::size_t follows = datagram.size() - kHeaderBytes;
  // A sender may pad the datagram, never cut it short.
  if (extra > follows) {
    return make_error("extra length " + std::to_string(extra) + " but " + std::to_string(follows) +
                      " bytes follow the header");
  }
  const ByteView data = datagram.subspan(kHeaderBytes, extra);
  switch (static_cast<PacketType>(datagram[4])) {
    case PacketType::MultiSync:
      return decode_sync(data);
    case PacketType::Ping:
      return decode_ping(data);
    default:
      return Packet{OtherPacket{datagram[4]}};
  }
}

Bytes encode_sync(const SyncPacket& packet) {
  const std::string name = packet.file_name.substr(0, kMaxFileName);
  Bytes out = header(PacketType::MultiSync, kSyncFixed + name.size() + 1);
  out.push_back(static_cast<std::uint8_t>(packet.action));
  out.push_back(static_cast<std::uint8_t>(packet.file));
  put_u32_le(out, packet.frame);
  put_u32_le(out, std::bit_cast<std::uint32_t>(packet.seconds));
  out.insert(out.end(), name.begin(), name.end());
  out.push_back(0);
  return out;
}

Bytes encode_ping(const PingPacket& packet) {
  Bytes extra(kPingV3Extra, 0);
  extra[0] = 3;
  extra[1] = packet.discover ? 1 : 0;
  extra[2] = packet.system_type;
  extra[3] = static_cast<std::uint8_t>(packet.major >> 8);
  extra[4] = static_cast<std::uint8_t>(packet.major & 0xff);
  extra[5] = static_cast<std::uint8_t>(packet.minor >> 8);
  extra[6] = static_cast<std::uint8_t>(packet.minor & 0xff);
  extra[7] = packet.mode;
  std::copy(packet.address.begin(), packet.address.end(), extra.begin() + 8);
  put_field(extra, kHostnameAt, kHostnameField, packet.hostname);
  put_field(extra, kVersionAt, kVersionField, packet.version_text);
  put_field(extra, kHardwareAt, kHardwareField, packet.hardware);
  put_field(extra, kRangesAt, kRangesField, packet.ranges);
  Bytes out = header(PacketType::Ping, kPingV3Extra);
  out.insert(out.end(), extra.begin(), extra.end());
  return out;
}

}  // namespace seqc::fpp
