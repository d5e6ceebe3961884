// An emulated Yahboom Raspblock driver board. It never replies (neither does the real board);
// it decodes what it receives with raspblock::PacketDecoder, rejects packets with a bad
// checksum (or an unknown function or length), and records:
//   - every raw chunk of bytes with its arrival time,
//   - every accepted packet and every rejection with its time,
//   - a timeline of state changes: PID settings, the two gimbal servos, single servos 1-4
//     and rocker x/y/z, each entry only when a value actually changes.
// Times are emulated: callers pass the arrival time of each chunk. The gimbal (function 02,
// length 4) and the single servos (function 02, length 3) are kept as separate state, since
// the document does not say whether the gimbal pair is two of the four single servos.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "base/bytes.hpp"
#include "protocol/raspblock/raspblock.hpp"
#include "runtime/io/clock.hpp"

namespace seqc::emu {

enum class RaspblockField : std::uint8_t {
  PidMode,
  SpeedKp,
  SpeedKi,
  PositionKp,
  PositionKi,
  PositionKd,
  YawKp,
  YawKi,
  YawKd,
  GimbalHorizontal,
  GimbalVertical,
  Servo1,
  Servo2,
  Servo3,
  Servo4,
  RockerX,
  RockerY,
  RockerZ,
};
inline constexpr std::size_t kRaspblockFieldCount = 18;

// "pid.mode", "gimbal.horizontal", "servo.1", "rocker.x", ...
std::string_view field_name(RaspblockField field);

struct RaspblockChange {
  io::TimePoint at{0};
  RaspblockField field = RaspblockField::PidMode;
  std::optional<int> previous;  // nullopt: never set before
  int value = 0;
  friend bool operator==(const RaspblockChange&, const RaspblockChange&) = default;
};

struct RaspblockPacketRecord {
  io::TimePoint at{0};
  raspblock::Packet packet;
};

struct RaspblockRejection {
  io::TimePoint at{0};
  std::string reason;
  bool bad_checksum = false;
};

struct RaspblockChunk {
  io::TimePoint at{0};
  Bytes bytes;
};

class RaspblockEmulator {
 public:
  // All `bytes` arrive at `at`.
  void receive(ByteView bytes, io::TimePoint at);

  const std::vector<RaspblockPacketRecord>& packets() const { return packets_; }
  const std::vector<RaspblockRejection>& rejections() const { return rejections_; }
  std::size_t bad_checksums() const;
  const std::vector<RaspblockChange>& timeline() const { return timeline_; }
  const std::vector<RaspblockChunk>& chunks() const { return chunks_; }
  Bytes received_bytes() const;
  // Current value of a field (nullopt: never set).
  std::optional<int> value(RaspblockField field) const;

 private:
  void apply(const raspblock::Packet& packet, io::TimePoint at);
  void set(RaspblockField field, int value, io::TimePoint at);

  raspblock::PacketDecoder decoder_;
  std::vector<RaspblockPacketRecord> packets_;
  std::vector<RaspblockRejection> rejections_;
  std::vector<RaspblockChange> timeline_;
  std::vector<RaspblockChunk> chunks_;
  std::optional<int> state_[kRaspblockFieldCount];
};

// One line for a person: "   12.345678 s  gimbal.horizontal 1500 -> 1600" (or "= 1600" for
// a first value).
std::string describe_change(const RaspblockChange& change);
// CSV with a header line: time_s,field,previous,value (previous empty when never set).
std::string timeline_csv(const std::vector<RaspblockChange>& timeline);

}  // namespace seqc::emu
