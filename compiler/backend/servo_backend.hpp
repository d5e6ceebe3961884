// What a ServoProgram becomes on the servo controller: a stored action group (GroupDownload)
// or, for live play, one MultiServoMove per keyframe.
#pragma once

#include <cstdint>
#include <optional>
#include <variant>
#include <vector>

#include "compiler/compile.hpp"
#include "runtime/protocol/bytes.hpp"
#include "runtime/protocol/group_download.hpp"
#include "runtime/protocol/lsc6_messages.hpp"
#include "runtime/protocol/lsc_messages.hpp"
#include "runtime/protocol/result.hpp"

namespace seqc::backend {

// One controller action per keyframe, in order.
std::vector<lsc::GroupAction> to_actions(const compiler::ServoProgram& program);

// A request of either controller dialect: the xArm / LSC-16 / LSC-32 one or the LSC-6 one.
using DialectRequest = std::variant<lsc::Request, lsc6::Request>;

// One packet of the download as the uploader sends it (and waits for its acknowledgement).
struct PlannedFrame {
  DialectRequest request;
  lsc::Frame frame;
  Bytes serial;                         // 55 55 LEN CMD DATA
  std::optional<std::size_t> keyframe;  // index into program.keyframes for step-4 packets
};

// True when the program's robot is an LSC-6 board, whose firmware speaks its own dialect.
bool uses_lsc6_dialect(const compiler::ServoProgram& program);

// The whole download of `program` into `group`, in send order: GroupDownload steps 1-5 built on
// lsc::plan_group_download, or for an LSC-6 one DownloadAction per action (lsc6::plan_download).
// Error if the program cannot be stored (empty, too many actions, an action too big for a
// frame, or one the LSC-6 would not play).
Result<std::vector<PlannedFrame>> plan_download(const compiler::ServoProgram& program,
                                                std::uint8_t group);

// Live play: one MultiServoMove per keyframe, sent `send_ms` after the start. Every servo the
// program uses appears in every move (ascending id); those the keyframe does not mention carry
// kNoMove.
struct TimedMove {
  std::uint32_t send_ms = 0;
  lsc::MultiServoMove move;
};
std::vector<TimedMove> live_moves(const compiler::ServoProgram& program);

// The ids of the servos the program moves, ascending.
std::vector<std::uint8_t> used_servo_ids(const compiler::ServoProgram& program);

}  // namespace seqc::backend
