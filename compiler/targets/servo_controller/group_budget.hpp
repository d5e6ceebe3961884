// The words of a dance that needs more actions than its groups hold (servo_lowering.cpp's
// errors): how many it needs and the groups hold, when the first action too many starts on the
// music's count, and, for a dance kept to one group, how a longer one is stored.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include "compiler/frontend/reporter.hpp"
#include "compiler/frontend/robot_section.hpp"
#include "compiler/targets/servo_controller/servo_lowering.hpp"
#include "compiler/timeline/tempo_map.hpp"

namespace seqc::compiler {

// " at 8.5 s (bar 5 beat 2)": `t` in seconds, and on the music's count when the file has bars.
std::string when_text(const TempoMap& map, ExactMs t);

// "the sequence needs at least 1021/1020 actions; a group holds ..., and this step makes action
// 1,021", or chained "the sequence needs at least 6,001 actions; the 5 groups it may take hold
// 5,100 (1,020 each), and this step makes action 5,101".
std::string budget_text(const Robot& robot, std::size_t capacity, std::size_t groups,
                        std::uint64_t needed, bool at_least);

// For a dance kept to one group: a note at its `sequence:` that `upload --run` chains groups.
std::optional<Reporter::Note> chain_hint(const ServoWalk& walk);

}  // namespace seqc::compiler
