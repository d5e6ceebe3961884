// The Raspblock's packet stream as text, for `seqc compile --emit hex|listing|json`: the frames
// planned by targets/raspblock/raspblock_stream.hpp, each with its send time, and in the listing
// what each packet means and the step it came from.
#pragma once

#include <string>
#include <vector>

#include "base/source.hpp"
#include "compiler/program/raspblock_program.hpp"
#include "compiler/targets/raspblock/raspblock_stream.hpp"

namespace seqc::compiler {

// One frame per line: the send time in ms right-aligned in 6 columns, " ms  ", then the bytes
// as lowercase hex: "     0 ms  ff fe 03 08 01 00 00 00 00 00 00 01 0d".
std::string render_stream_hex(const std::vector<StreamFrame>& frames);

// The hex line of each frame followed by what it means and the step it came from:
//   "   500 ms  ff fe 02 04 ...  GimbalServos horizontal=1600 vertical=1500  (car.yaml:12:5)"
std::string render_stream_listing(const compiler::RaspblockProgram& program,
                                  const std::vector<StreamFrame>& frames,
                                  const seqc::SourceManager& sources);

// {"robot": "raspblock", "baud": 115200, "duration_ms": N, "bytes": N,
//  "frames": [{"at_ms": 0, "hex": "ff fe ...", "packet": "Rocker x=0 y=0 z=0"}, ...]}
std::string render_stream_json(const compiler::RaspblockProgram& program,
                               const std::vector<StreamFrame>& frames);

}  // namespace seqc::compiler
