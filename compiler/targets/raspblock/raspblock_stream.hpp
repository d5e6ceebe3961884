// What a RaspblockProgram becomes on the wire: one frame per packet with its send time, as
// `seqc play` sends them (formats/raspblock_listing.hpp prints them for `seqc compile --emit`).
#pragma once

#include <cstdint>
#include <vector>

#include "base/source.hpp"
#include "compiler/program/raspblock_program.hpp"
#include "base/bytes.hpp"
#include "base/result.hpp"

namespace seqc::compiler {

struct StreamFrame {
  std::uint32_t at_ms = 0;  // send time from the start of the play
  Bytes bytes;              // FF FE FUNC LEN DATA CHK
};

// Every packet encoded, in send order. An error only if a packet is out of range, which the
// compiler never lets through (so it means a bug).
Result<std::vector<StreamFrame>> plan_stream(const compiler::RaspblockProgram& program);

// The frame that stops the car (Rocker 0,0,0): the last frame of every stream, and what a
// player sends when a play is interrupted.
Bytes stop_frame();

}  // namespace seqc::compiler
