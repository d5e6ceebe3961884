// The Raspblock car's settings that are not positions: the 'pid' section of the main file and
// the speeds of a 'drive' step (docs/protocol/raspblock.md). Each parser reports what is
// wrong and returns nullopt.
#pragma once

#include <optional>

#include "compiler/frontend/reporter.hpp"
#include "compiler/frontend/yaml/yaml_tree.hpp"
#include "protocol/raspblock/raspblock.hpp"

namespace seqc::compiler {

// 'pid': mode (speed or position) and all eight gains, 0-255 each.
std::optional<raspblock::PidAdjust> parse_pid_section(const YamlNode& pid, Reporter& reporter);

// 'drive: {x, y, z}': x and y -25 to 25, z -200 to 200; an axis not given is 0.
std::optional<raspblock::Rocker> parse_drive(const YamlNode& drive, Reporter& reporter);

}  // namespace seqc::compiler
