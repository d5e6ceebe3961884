// Human- and machine-readable forms of a compiled download: the labelled listing
// (`seqc compile --emit listing`), the hex dump (`--emit hex`) and JSON (`--emit json`).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "base/source.hpp"
#include "compiler/program/program.hpp"
#include "compiler/targets/servo_controller/servo_wire.hpp"

namespace seqc::compiler {

// One serial frame per line: lowercase two-digit hex separated by single spaces, send order.
std::string render_hex(const std::vector<PlannedFrame>& plan);

// Every frame with every field labelled, and for the frames that store an action the action it
// carries (start time, servo name and id, position, the source line). `storage` ends the
// heading's count of actions, as the board stores them: " in 2 blocks", " (LSC-6 dialect)".
std::string render_listing(const compiler::ServoProgram& program,
                           const std::vector<PlannedFrame>& plan, std::uint8_t group,
                           const seqc::SourceManager& sources, std::string_view storage);

// {"robot": ..., "group": ..., "duration_ms": ..., "servos": [...], "keyframes": [...],
//  "frames": ["55 55 ...", ...]}
std::string render_json(const compiler::ServoProgram& program,
                        const std::vector<PlannedFrame>& plan, std::uint8_t group,
                        const seqc::SourceManager& sources);

// "walk.yaml:12:5" for a location (or "" for none).
std::string location_text(const seqc::Location& at, const seqc::SourceManager& sources);

}  // namespace seqc::compiler
