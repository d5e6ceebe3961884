// Typed messages of the LSC-6 / LeArm controller dialect (docs/protocol/lsc-6.md): the family's
// older six-channel PWM boards. The frame is the family's (55 55 LEN CMD DATA, no checksum, see
// lsc_frame.hpp), but the command set, the group download and every answer differ from the
// xArm dialect of lsc_messages.hpp, so the two never share a message type.
//
// Host -> board:   Move (CMD 3), Run (6), Stop (7), EraseAll (8), DownloadAction (25).
// Board -> host:   always the four bytes 55 55 02 <cmd>: RunAccepted (6), GroupFinished (7),
//                  Erased (8), ActionStored (25).
// encode() checks every value against what the board stores or acts on and fails rather than
// wrapping; decode_request()/decode_reply() are direction-specific (CMD 7 and 8 travel both
// ways).
#pragma once

#include <cstdint>
#include <string>
#include <variant>
#include <vector>

#include "protocol/lsc/lsc_frame.hpp"
#include "base/result.hpp"
#include "protocol/servo_target.hpp"

namespace seqc::lsc6 {

using lsc::Frame;

enum class Command : std::uint8_t {
  Move = 0x03,
  Run = 0x06,
  Stop = 0x07,
  EraseAll = 0x08,
  DownloadAction = 0x19,
};

// What the board stores and plays (docs/protocol/lsc-6.md, "Limits").
inline constexpr unsigned kGroups = 256;
inline constexpr unsigned kMaxActions = 255;        // the TOTAL byte
inline constexpr unsigned kMaxServosPerAction = 8;  // the player stops at an action with more
inline constexpr std::uint8_t kFirstChannel = 1;    // PWM outputs wired on the board
inline constexpr std::uint8_t kLastChannel = 6;
inline constexpr std::uint16_t kMinPulse = 500;  // µs; the board ignores a target outside
inline constexpr std::uint16_t kMaxPulse = 2500;
inline constexpr std::uint16_t kMinTime = 20;  // ms; the board clamps a time outside
inline constexpr std::uint16_t kMaxTime = 30000;
// One stored action is a 64-byte flash slot holding N tLo tHi {id pLo pHi}xN.
inline constexpr std::size_t kSlotBytes = 64;

// id: the PWM channel (kFirstChannel..kLastChannel); position: the pulse in µs.
using Target = lsc::ServoTarget;

// ---- Requests (host -> board) -----------------------------------------------------------

struct Move {  // 55 55 LEN 03 N tLo tHi {id pLo pHi}xN; no answer
  std::uint16_t time_ms = 0;
  std::vector<Target> servos;
  friend bool operator==(const Move&, const Move&) = default;
};
struct Run {  // 55 55 05 06 G cntLo cntHi
  std::uint8_t group = 0;
  std::uint16_t times = 1;  // 0 = loop until stopped
  friend bool operator==(const Run&, const Run&) = default;
};
struct Stop {  // 55 55 02 07; no answer
  friend bool operator==(const Stop&, const Stop&) = default;
};
struct EraseAll {  // 55 55 02 08: wipes the action count of EVERY group
  friend bool operator==(const EraseAll&, const EraseAll&) = default;
};
struct DownloadAction {  // 55 55 LEN 19 G TOTAL IDX N tLo tHi {id pLo pHi}xN
  std::uint8_t group = 0;
  std::uint8_t total = 1;  // actions in the group, 1..255
  std::uint8_t index = 0;  // 0-based, < total
  std::uint16_t time_ms = 0;
  std::vector<Target> servos;  // 0..8 (none: a pause)
  friend bool operator==(const DownloadAction&, const DownloadAction&) = default;
};

using Request = std::variant<Move, Run, Stop, EraseAll, DownloadAction>;

// ---- Answers (board -> host), each 55 55 02 <cmd> -------------------------------------------

struct RunAccepted {  // sent before playback starts, even for an empty group; some copies never
  friend bool operator==(const RunAccepted&, const RunAccepted&) = default;
};
struct GroupFinished {  // unprompted, when a counted run ends; some copies never send it
  friend bool operator==(const GroupFinished&, const GroupFinished&) = default;
};
struct Erased {
  friend bool operator==(const Erased&, const Erased&) = default;
};
struct ActionStored {  // after the flash write of one DownloadAction; it names no index
  friend bool operator==(const ActionStored&, const ActionStored&) = default;
};

using Reply = std::variant<RunAccepted, GroupFinished, Erased, ActionStored>;

// ---- Codec ------------------------------------------------------------------------------

Result<Frame> encode(const Request& request);
Frame encode(const Reply& reply);
Result<Request> decode_request(const Frame& frame);
Result<Reply> decode_reply(const Frame& frame);
Result<Bytes> encode_serial(const Request& request);
Bytes encode_serial(const Reply& reply);

// One line naming the message and its fields, e.g. "Run group=0 times=1".
std::string describe(const Request& request);
std::string describe(const Reply& reply);

// The frames that store `actions` (each a time and its targets) in `group`, in order, or the
// first reason the board could not store them (too many actions, too many servos in one, a
// channel, pulse or time it would ignore or change).
struct PlannedAction {
  std::uint16_t time_ms = 0;
  std::vector<Target> servos;
};
Result<std::vector<DownloadAction>> plan_download(std::uint8_t group,
                                                  const std::vector<PlannedAction>& actions);

}  // namespace seqc::lsc6
