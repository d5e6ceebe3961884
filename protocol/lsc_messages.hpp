// Typed messages for every command of the servo controller (docs/protocol/servo-controller.md),
// both directions, plus the unsolicited group notifications (docs/protocol/servo-controller.md).
//
// encode() checks every value against its field and fails rather than wrapping or clamping.
// A Frame means different things per direction (CMD 5/6/7/8 are both requests and replies),
// so decoding is direction-specific: decode_request() for what the host sends,
// decode_reply() for what the controller sends.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "protocol/lsc/lsc_frame.hpp"
#include "base/result.hpp"
#include "protocol/servo_target.hpp"

namespace seqc::lsc {

enum class Command : std::uint8_t {
  MultiServoMove = 0x03,
  GroupDownload = 0x05,
  GroupRun = 0x06,
  GroupStop = 0x07,
  GroupErase = 0x08,
  GroupSpeed = 0x0b,
  GetBatteryVoltage = 0x0f,
  MultiServoOff = 0x14,
  ServoPositionRead = 0x15,
  ServoOffsetWrite = 0x16,
  ServoOffsetRead = 0x17,
  ServoOffsetAdjust = 0x18,
  ServoSpeed = 0x1a,
  BusServoInfoWrite = 0x1b,
  BusServoInfoRead = 0x1c,
};

// MultiServoMove's "do not move this servo" value (wire bytes 00 ff).
inline constexpr std::uint16_t kNoMove = 0xff00;
// GroupErase's "all groups".
inline constexpr std::uint8_t kAllGroups = 0xff;

// ---- Requests (host -> controller) -------------------------------------------------------

struct MultiServoMove {
  struct Entry {
    std::uint8_t id = 0;
    std::optional<std::uint16_t> position;  // nullopt = kNoMove; an explicit 0xff00 is an error
    friend bool operator==(const Entry&, const Entry&) = default;
  };
  std::uint16_t time_ms = 0;
  std::vector<Entry> servos;
  friend bool operator==(const MultiServoMove&, const MultiServoMove&) = default;
};

// GroupDownload steps 1-5; their byte layout is the project's reading of the document and lives
// in group_download.cpp (see group_download.hpp).
struct GroupDownloadOpen {  // step 1
  std::uint8_t group = 0;
  std::vector<std::uint8_t> block_counts;  // one per used block, 1..4 entries, each 1..255
  friend bool operator==(const GroupDownloadOpen&, const GroupDownloadOpen&) = default;
};
struct GroupDownloadSize {  // step 2, once per block
  std::uint8_t group = 0;
  std::uint8_t block = 0;
  std::uint8_t count = 0;
  friend bool operator==(const GroupDownloadSize&, const GroupDownloadSize&) = default;
};
struct GroupDownloadBlocks {  // step 3
  std::uint8_t group = 0;
  std::uint8_t block_count = 0;  // 1..4
  friend bool operator==(const GroupDownloadBlocks&, const GroupDownloadBlocks&) = default;
};
struct GroupDownloadAction {  // step 4, once per action
  std::uint8_t group = 0;
  std::uint8_t block = 0;
  std::uint8_t index = 0;  // 0-based within the block
  std::uint16_t time_ms = 0;
  std::vector<ServoTarget> servos;
  friend bool operator==(const GroupDownloadAction&, const GroupDownloadAction&) = default;
};
struct GroupDownloadClose {  // step 5
  std::uint8_t group = 0;
  friend bool operator==(const GroupDownloadClose&, const GroupDownloadClose&) = default;
};

struct GroupRun {
  std::uint8_t group = 0;
  std::uint16_t times = 0;  // 0 = loop until stopped
  friend bool operator==(const GroupRun&, const GroupRun&) = default;
};
struct GroupStop {
  friend bool operator==(const GroupStop&, const GroupStop&) = default;
};
struct GroupErase {
  std::uint8_t group = 0;  // kAllGroups = every group
  friend bool operator==(const GroupErase&, const GroupErase&) = default;
};
struct GroupSpeed {
  std::uint8_t group = 0;  // kAllGroups = every group
  std::uint16_t percent = 100;
  friend bool operator==(const GroupSpeed&, const GroupSpeed&) = default;
};
struct GetBatteryVoltage {
  friend bool operator==(const GetBatteryVoltage&, const GetBatteryVoltage&) = default;
};
struct MultiServoOff {
  std::vector<std::uint8_t> servos;
  friend bool operator==(const MultiServoOff&, const MultiServoOff&) = default;
};
struct ServoPositionRead {
  std::vector<std::uint8_t> servos;
  friend bool operator==(const ServoPositionRead&, const ServoPositionRead&) = default;
};
struct ServoOffsetWrite {  // persists the current offsets of these servos
  std::vector<std::uint8_t> servos;
  friend bool operator==(const ServoOffsetWrite&, const ServoOffsetWrite&) = default;
};
struct ServoOffsetRead {
  std::vector<std::uint8_t> servos;
  friend bool operator==(const ServoOffsetRead&, const ServoOffsetRead&) = default;
};
struct ServoOffsetAdjust {  // volatile: lost at power-off unless written
  std::uint8_t servo = 0;
  std::int16_t offset = 0;
  // reading (docs/protocol/readings.md): `id offset:sbyte`, the one-byte form a public arm
  // library sends, is accepted too; set, the frame carries that form (offset -128..127).
  bool one_byte = false;
  friend bool operator==(const ServoOffsetAdjust&, const ServoOffsetAdjust&) = default;
};
enum class ServoMode : std::uint8_t { Servo = 0, Motor = 1 };
struct ServoSpeed {
  std::uint8_t servo = 0;
  ServoMode mode = ServoMode::Servo;
  std::uint16_t milliseconds = 0;
  friend bool operator==(const ServoSpeed&, const ServoSpeed&) = default;
};
struct BusServoLimits {
  std::uint16_t position_min = 0;
  std::uint16_t position_max = 1000;
  std::uint16_t millivolts_min = 0;
  std::uint16_t millivolts_max = 0;
  std::uint16_t temp_max = 0;
  std::uint8_t led_status = 0;   // 0 = enable, 1 = disable
  std::uint8_t led_warning = 0;  // bits: 0 overheat, 1 overvoltage, 2 overposition
  friend bool operator==(const BusServoLimits&, const BusServoLimits&) = default;
};
struct BusServoInfoWrite {  // reaches every servo on the bus
  std::uint8_t servo = 0;
  BusServoLimits limits;
  // reading (docs/protocol/readings.md): the frame carries the id alone (`55 55 03 1B id`), as a
  // public arm library sends it to set a servo's id; every servo on the bus takes that id and
  // `limits` is unused.
  bool id_only = false;
  friend bool operator==(const BusServoInfoWrite&, const BusServoInfoWrite&) = default;
};
struct BusServoInfoRead {
  friend bool operator==(const BusServoInfoRead&, const BusServoInfoRead&) = default;
};

using Request = std::variant<MultiServoMove, GroupDownloadOpen, GroupDownloadSize,
                             GroupDownloadBlocks, GroupDownloadAction, GroupDownloadClose, GroupRun,
                             GroupStop, GroupErase, GroupSpeed, GetBatteryVoltage, MultiServoOff,
                             ServoPositionRead, ServoOffsetWrite, ServoOffsetRead,
                             ServoOffsetAdjust, ServoSpeed, BusServoInfoWrite, BusServoInfoRead>;

// ---- Replies and notifications (controller -> host) --------------------------------------

struct GroupDownloadAck {  // 55 55 04 05 <step> <status>
  std::uint8_t step = 0;
  std::uint8_t status = 0;  // 0 = accepted; anything else is a refusal
  bool accepted() const { return status == 0; }
  friend bool operator==(const GroupDownloadAck&, const GroupDownloadAck&) = default;
};
struct GroupStarted {  // unsolicited, CMD 6
  std::uint8_t group = 0;
  std::uint16_t times = 0;
  friend bool operator==(const GroupStarted&, const GroupStarted&) = default;
};
struct GroupStopped {  // unsolicited, CMD 7; some boards send no data
  struct Detail {
    std::uint8_t group = 0;
    std::uint16_t times = 0;
    friend bool operator==(const Detail&, const Detail&) = default;
  };
  std::optional<Detail> detail;
  friend bool operator==(const GroupStopped&, const GroupStopped&) = default;
};
struct GroupFinished {  // unsolicited, CMD 8 with 3 data bytes
  std::uint8_t group = 0;
  std::uint16_t times = 0;
  friend bool operator==(const GroupFinished&, const GroupFinished&) = default;
};
struct GroupErased {  // CMD 8 with no data: GroupErase's "empty response"
  friend bool operator==(const GroupErased&, const GroupErased&) = default;
};
struct BatteryVoltage {
  std::uint16_t millivolts = 0;
  friend bool operator==(const BatteryVoltage&, const BatteryVoltage&) = default;
};
struct ServoPositions {
  std::vector<ServoTarget> servos;
  friend bool operator==(const ServoPositions&, const ServoPositions&) = default;
};
struct ServoOffsets {
  struct Entry {
    std::uint8_t id = 0;
    std::int8_t offset = 0;
    friend bool operator==(const Entry&, const Entry&) = default;
  };
  std::vector<Entry> servos;
  friend bool operator==(const ServoOffsets&, const ServoOffsets&) = default;
};
struct BusServoInfo {
  std::uint8_t id = 0;
  BusServoLimits limits;
  std::int8_t offset = 0;  // reading: the document's (byte) offset is two's complement
  std::uint16_t position = 0;
  std::uint8_t temp = 0;
  std::uint16_t millivolts = 0;
  friend bool operator==(const BusServoInfo&, const BusServoInfo&) = default;
};

using Reply = std::variant<GroupDownloadAck, GroupStarted, GroupStopped, GroupFinished, GroupErased,
                           BatteryVoltage, ServoPositions, ServoOffsets, BusServoInfo>;

// ---- Codec ---------------------------------------------------------------------------------

Result<Frame> encode(const Request& request);
Result<Frame> encode(const Reply& reply);
Result<Request> decode_request(const Frame& frame);
Result<Reply> decode_reply(const Frame& frame);

// Convenience: encode straight to serial bytes.
Result<Bytes> encode_serial(const Request& request);
Result<Bytes> encode_serial(const Reply& reply);

// One line naming the message and every field, for listings, verbose output and traces,
// e.g. "GroupRun group=0 times=1".
std::string describe(const Request& request);
std::string describe(const Reply& reply);

// Range-checked narrowing for values that come from users (CLI arguments, YAML).
Result<std::uint8_t> checked_u8(long long value, const char* field);
Result<std::uint16_t> checked_u16(long long value, const char* field);
Result<std::int16_t> checked_i16(long long value, const char* field);

}  // namespace seqc::lsc
