// Falcon Player (FPP) control packets on UDP 32320 (docs/protocol/fpp-multisync.md, from FPP's
// docs/ControlProtocol.txt): the 7-byte header "FPPD", type, extra length (little-endian), then
// the extra data. seqc reads MultiSync packets (a master's open/start/sync/stop of a sequence or
// media file) and pings (a master's discovery), and writes the ping a remote answers with.
// Decoding never reads past the datagram and refuses any length that disagrees with it; no I/O.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <variant>

#include "base/bytes.hpp"
#include "base/result.hpp"

namespace seqc::fpp {

inline constexpr std::uint16_t kControlPort = 32320;
// 239.70.80.80: "239.F.P.P".
inline constexpr std::array<std::uint8_t, 4> kMulticastGroup = {239, 70, 80, 80};
inline constexpr std::size_t kHeaderBytes = 7;
// The longest datagram decoded: FPP's own send buffer for a sync packet.
inline constexpr std::size_t kMaxPacketBytes = 2048;
// The longest file name a sync packet may carry (FPP keeps file names to this on its disk).
inline constexpr std::size_t kMaxFileName = 255;

enum class PacketType : std::uint8_t {
  Command = 0x00,
  MultiSync = 0x01,
  Event = 0x02,
  Blank = 0x03,
  Ping = 0x04,
  Plugin = 0x05,
  FppCommand = 0x06,
};

// The document's codes: 0 start, 1 stop, 2 sync, 3 open.
enum class SyncAction : std::uint8_t { Start = 0, Stop = 1, Sync = 2, Open = 3 };
enum class SyncFile : std::uint8_t { Sequence = 0, Media = 1 };

struct SyncPacket {
  SyncAction action = SyncAction::Sync;
  SyncFile file = SyncFile::Sequence;
  std::uint32_t frame = 0;  // the master's frame of the sequence
  float seconds = 0;        // seconds elapsed since the file's start
  std::string file_name;    // as the master names it: "show.fseq", "song.mp3"
  friend bool operator==(const SyncPacket&, const SyncPacket&) = default;
};

// Operating mode bits of a ping.
inline constexpr std::uint8_t kModeBridge = 0x01;
inline constexpr std::uint8_t kModePlayer = 0x02;
inline constexpr std::uint8_t kModeSendsMultiSync = 0x04;
inline constexpr std::uint8_t kModeRemote = 0x08;
// System type of a system that is neither FPP nor known hardware ("other systems").
inline constexpr std::uint8_t kSystemOther = 0xC0;
// Extra-data lengths of a version 3 ping (what seqc writes) and of the shortest, version 1.
inline constexpr std::size_t kPingV3Extra = 294;
inline constexpr std::size_t kPingV1Extra = 98;

struct PingPacket {
  std::uint8_t version = 3;
  bool discover = false;  // a master asking every remote to ping back
  std::uint8_t system_type = kSystemOther;
  std::uint16_t major = 0;
  std::uint16_t minor = 0;
  std::uint8_t mode = kModeRemote;
  std::array<std::uint8_t, 4> address{};  // 0.0.0.0: not an instance to list
  std::string hostname;                   // at most 64 bytes
  std::string version_text;               // at most 40 bytes
  std::string hardware;                   // at most 40 bytes
  std::string ranges;                     // at most 120 bytes (version 3)
  friend bool operator==(const PingPacket&, const PingPacket&) = default;
};

// A packet of a type seqc does not act on: its type, so it can be counted.
struct OtherPacket {
  std::uint8_t type = 0;
  friend bool operator==(const OtherPacket&, const OtherPacket&) = default;
};

using Packet = std::variant<SyncPacket, PingPacket, OtherPacket>;

// Errors name the first thing wrong: "not an FPP packet (no FPPD header)", "extra length 40 but
// 12 bytes follow the header", "sync packet: file name without its NUL", ...
Result<Packet> decode(ByteView datagram);

// A sync packet as a master writes it (for tests and the end-to-end master); names longer than
// kMaxFileName are cut.
Bytes encode_sync(const SyncPacket& packet);
// A version 3 ping, kPingV3Extra bytes of extra data; strings longer than their fields are cut.
Bytes encode_ping(const PingPacket& packet);

}  // namespace seqc::fpp
