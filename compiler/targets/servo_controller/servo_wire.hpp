// What a ServoProgram becomes on a servo controller, per dialect: a stored action group
// (GroupDownload steps on the xArm / LSC-16 / LSC-32, one DownloadAction per action on the
// LSC-6) or, for live play, one timed move per keyframe (MultiServoMove, or the LSC-6's Move).
// Which dialect a program goes to is not decided here: the caller picks the function.
#pragma once

#include <cstdint>
#include <optional>
#include <variant>
#include <vector>

#include "compiler/program/program.hpp"
#include "base/bytes.hpp"
#include "protocol/lsc/group_download.hpp"
#include "protocol/lsc6/lsc6_messages.hpp"
#include "protocol/lsc/lsc_messages.hpp"
#include "protocol/planned_frame.hpp"
#include "base/result.hpp"

namespace seqc::compiler {

// One controller action per keyframe, in order.
std::vector<lsc::GroupAction> to_actions(const compiler::ServoProgram& program);

// One packet of the download as the uploader sends it (protocol/planned_frame.hpp).
using seqc::DialectRequest;
using seqc::PlannedFrame;

// The GroupDownload of `program` into `group`, in send order (steps 1-5 built on
// lsc::plan_group_download). Error if the program cannot be stored (empty, too many actions, an
// action too big for a frame).
Result<std::vector<PlannedFrame>> plan_download(const compiler::ServoProgram& program,
                                                std::uint8_t group);

// The LSC-6 download of `program` into `group`: one DownloadAction per keyframe
// (lsc6::plan_download). Error if the board would not store or play an action.
Result<std::vector<PlannedFrame>> plan_lsc6_download(const compiler::ServoProgram& program,
                                                     std::uint8_t group);

// Live play: one MultiServoMove per keyframe, sent `send_ms` after the start. Every servo the
// program uses appears in every move (ascending id); those the keyframe does not mention carry
// kNoMove.
struct TimedMove {
  std::uint32_t send_ms = 0;
  lsc::MultiServoMove move;
};
std::vector<TimedMove> live_moves(const compiler::ServoProgram& program);

// Live play on an LSC-6: one Move per keyframe, sent `send_ms` after the start, carrying only
// the servos the keyframe names (the LSC-6 has no "no move" entry).
struct TimedLsc6Move {
  std::uint32_t send_ms = 0;
  lsc6::Move move;
};
std::vector<TimedLsc6Move> live_lsc6_moves(const compiler::ServoProgram& program);

// The ids of the servos the program moves, ascending.
std::vector<std::uint8_t> used_servo_ids(const compiler::ServoProgram& program);

}  // namespace seqc::compiler
