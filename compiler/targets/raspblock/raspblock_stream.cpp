#include "compiler/targets/raspblock/raspblock_stream.hpp"

#include "protocol/raspblock/raspblock.hpp"

namespace seqc::compiler {

Result<std::vector<StreamFrame>> plan_stream(const compiler::RaspblockProgram& program) {
  std::vector<StreamFrame> frames;
  frames.reserve(program.packets.size());
  for (const compiler::TimedPacket& p : program.packets) {
    auto bytes = raspblock::encode(p.packet);
    if (!bytes) return make_error("internal error: " + bytes.error().message);
    frames.push_back(StreamFrame{p.at_ms, std::move(*bytes)});
  }
  return frames;
}

Bytes stop_frame() { return raspblock::encode(raspblock::Rocker{0, 0, 0}).value(); }

}  // namespace seqc::compiler
