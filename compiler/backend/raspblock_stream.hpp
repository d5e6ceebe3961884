// What a RaspblockProgram becomes on the wire: one frame per packet with its send time, as
// `seqc play` sends them and `seqc compile --emit hex|listing|json` prints them.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "compiler/raspblock_program.hpp"
#include "compiler/source/source.hpp"
#include "runtime/protocol/bytes.hpp"
#include "runtime/protocol/result.hpp"

namespace seqc::backend {

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

// One frame per line: the send time in ms right-aligned in 6 columns, " ms  ", then the bytes
// as lowercase hex: "     0 ms  ff fe 03 08 01 00 00 00 00 00 00 01 0d".
std::string render_stream_hex(const std::vector<StreamFrame>& frames);

// The hex line of each frame followed by what it means and the step it came from:
//   "   500 ms  ff fe 02 04 ...  GimbalServos horizontal=1600 vertical=1500  (car.yaml:12:5)"
std::string render_stream_listing(const compiler::RaspblockProgram& program,
                                  const std::vector<StreamFrame>& frames,
                                  const compiler::SourceManager& sources);

// {"robot": "raspblock", "baud": 115200, "duration_ms": N, "bytes": N,
//  "frames": [{"at_ms": 0, "hex": "ff fe ...", "packet": "Rocker x=0 y=0 z=0"}, ...]}
std::string render_stream_json(const compiler::RaspblockProgram& program,
                               const std::vector<StreamFrame>& frames);

}  // namespace seqc::backend
