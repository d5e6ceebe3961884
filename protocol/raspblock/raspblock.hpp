// Yahboom Raspblock driver board packets (docs/protocol/raspblock.md).
//
//   FF FE FUNC LEN DATA... CHK     LEN = len(DATA), CHK = (FUNC + LEN + sum(DATA)) & 0xFF
// 16-bit fields are big-endian (unlike the servo controller). The board never replies.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <optional>
#include <string>
#include <variant>

#include "base/bytes.hpp"
#include "base/result.hpp"

namespace seqc::raspblock {

inline constexpr std::uint8_t kHeader0 = 0xff;
inline constexpr std::uint8_t kHeader1 = 0xfe;
inline constexpr std::uint32_t kBaud = 115200;

enum class Function : std::uint8_t { Pid = 0x01, Servo = 0x02, Rocker = 0x03 };
enum class PidMode : std::uint8_t { Speed = 0, Position = 1 };

struct PidAdjust {  // FUNC 01, LEN 9
  PidMode mode = PidMode::Speed;
  std::uint8_t speed_kp = 0, speed_ki = 0;
  std::uint8_t position_kp = 0, position_ki = 0, position_kd = 0;
  std::uint8_t yaw_kp = 0, yaw_ki = 0, yaw_kd = 0;
  friend bool operator==(const PidAdjust&, const PidAdjust&) = default;
};
struct GimbalServos {               // FUNC 02, LEN 4: Servo_control(angle_1, angle_2)
  std::uint16_t horizontal = 1500;  // 500..2500
  std::uint16_t vertical = 1500;    // 500..1950
  friend bool operator==(const GimbalServos&, const GimbalServos&) = default;
};
struct SingleServo {              // FUNC 02, LEN 3: Servo_control_single(index, angle)
  std::uint8_t index = 1;         // 1..4
  std::uint16_t position = 1500;  // 500..2500
  friend bool operator==(const SingleServo&, const SingleServo&) = default;
};
struct Rocker {  // FUNC 03, LEN 8, mode 01: magnitudes, signs in the direction byte 0b00000XYZ
  int x = 0;     // -25..25, right positive
  int y = 0;     // -25..25, up positive
  int z = 0;     // reading: -200..200 (magnitude 0-200 as documented), clockwise positive
  friend bool operator==(const Rocker&, const Rocker&) = default;
};

using Packet = std::variant<PidAdjust, GimbalServos, SingleServo, Rocker>;

// Range-checked: an out-of-range field is an error, never clamped.
Result<Bytes> encode(const Packet& packet);
// Decodes exactly one whole packet; rejects a bad checksum, unknown function or length.
Result<Packet> decode(ByteView bytes);
std::string describe(const Packet& packet);

// Streaming decoder: bytes in any chunking; resynchronises on FF FE after garbage or a bad
// packet. Each next() yields a decoded packet or the error that rejected one.
class PacketDecoder {
 public:
  void feed(ByteView bytes);
  std::optional<Result<Packet>> next();
  std::size_t skipped_bytes() const { return skipped_; }

 private:
  std::deque<std::uint8_t> buf_;
  std::size_t skipped_ = 0;
};

}  // namespace seqc::raspblock
