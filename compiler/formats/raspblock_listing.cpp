#include "compiler/formats/raspblock_listing.hpp"

#include <algorithm>
#include <cstdio>

#include "base/terminal_text.hpp"
#include "compiler/formats/listing.hpp"
#include "protocol/raspblock/raspblock.hpp"

namespace seqc::compiler {
namespace {

std::string time_column(std::uint32_t at_ms) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%6u ms  ", static_cast<unsigned>(at_ms));
  return buf;
}

std::string json_string(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

}  // namespace

std::string render_stream_hex(const std::vector<StreamFrame>& frames) {
  std::string out;
  for (const StreamFrame& f : frames) out += time_column(f.at_ms) + to_hex(f.bytes) + "\n";
  return out;
}

std::string render_stream_listing(const compiler::RaspblockProgram& program,
                                  const std::vector<StreamFrame>& frames,
                                  const seqc::SourceManager& sources) {
  std::string out;
  std::size_t bytes = 0;
  for (std::size_t i = 0; i < frames.size() && i < program.packets.size(); ++i) {
    const compiler::TimedPacket& p = program.packets[i];
    bytes += frames[i].bytes.size();
    std::string hex = to_hex(frames[i].bytes);
    hex.resize(std::max<std::size_t>(hex.size(), 41), ' ');
    out += time_column(frames[i].at_ms) + hex + "  " + raspblock::describe(p.packet);
    const std::string where = seqc::terminal_safe(location_text(p.source, sources));
    if (!where.empty()) out += "  (" + where + ")";
    out += "\n";
  }
  out += std::to_string(frames.size()) + " frames, " + std::to_string(bytes) + " bytes, " +
         std::to_string(program.duration_ms) + " ms at " + std::to_string(raspblock::kBaud) +
         " baud\n";
  return out;
}

std::string render_stream_json(const compiler::RaspblockProgram& program,
                               const std::vector<StreamFrame>& frames) {
  std::size_t bytes = 0;
  for (const StreamFrame& f : frames) bytes += f.bytes.size();
  std::string out = "{\"robot\": \"raspblock\", \"baud\": " + std::to_string(raspblock::kBaud) +
                    ", \"duration_ms\": " + std::to_string(program.duration_ms) +
                    ", \"bytes\": " + std::to_string(bytes) + ", \"frames\": [";
  for (std::size_t i = 0; i < frames.size() && i < program.packets.size(); ++i) {
    out += i == 0 ? "\n  " : ",\n  ";
    out += "{\"at_ms\": " + std::to_string(frames[i].at_ms) +
           ", \"hex\": " + json_string(to_hex(frames[i].bytes)) +
           ", \"packet\": " + json_string(raspblock::describe(program.packets[i].packet)) + "}";
  }
  out += frames.empty() ? "]}\n" : "\n]}\n";
  return out;
}

}  // namespace seqc::compiler
