// The first move is safe: the robot may be anywhere when a sequence starts, so before `seqc
// play` starts one on a board whose servos report their positions (the xArm family's bus servos,
// xarm_queries.hpp's readable_servos), the servos are read (ServoPositionRead) and each one's
// first move is worked out from where it is: from the reading to its first target over the time
// of the keyframe that first names it. The first such move faster than the servo's max_speed (in
// keyframe order, then by id) is returned; the caller refuses to start. Boards or servos that
// cannot report a position, and a read that is not answered, give no finding: the compiler's
// own first-move warning (from the far end of the limits) is all there is then.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "compiler/compile.hpp"
#include "runtime/boards/board.hpp"

namespace seqc::boards {

struct FirstMoveTooFast {
  std::uint8_t id = 0;
  std::string name;        // the servo's name in the program's robot
  std::uint16_t from = 0;  // where the servo reported it is
  std::uint16_t to = 0;    // its first target
  std::uint16_t time_ms = 0;
  double speed = 0;  // units per second from `from` to `to` in time_ms
  double max_speed = 0;
};

// Reads the positions over `line` (only on a board with queries) and checks every servo's first
// move; nullopt when none is too fast or nothing could be read.
std::optional<FirstMoveTooFast> first_move_too_fast(const Board& board, const Line& line,
                                                    const compiler::ServoProgram& program);

// Where the servos `ids` stand, read over `line` (ServoPositionRead) before a run compiles a
// first move relative to it (compiler::RobotStart): id -> position; nullopt when the board
// cannot be read, the read is not answered, or a servo does not answer.
std::optional<std::map<std::uint8_t, std::uint16_t>> read_start(
    const Board& board, const Line& line, const std::vector<std::uint8_t>& ids);

// As first_move_too_fast for the program `output` is, unless `force` (--force): nullopt then,
// and for an output that is not a servo program.
std::optional<FirstMoveTooFast> run_too_fast(const Board& board, const Line& line,
                                             const compiler::CompileOutput& output, bool force);

}  // namespace seqc::boards
