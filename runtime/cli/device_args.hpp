// How the device commands name a servo in a sentence. What a servo controller accepts as servos,
// targets, times and groups, and the --timeout syntax, are the boards library's
// (runtime/boards/servo_args.hpp).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "compiler/compile.hpp"

namespace seqc::cli {

// "servo 1" or, with a profile, "servo 1 (claw)".
std::string servo_label(std::uint8_t id, const std::optional<compiler::RobotInfo>& robot);
// "servo 1, servo 2 (elbow)".
std::string servo_labels(const std::vector<std::uint8_t>& ids,
                         const std::optional<compiler::RobotInfo>& robot);

}  // namespace seqc::cli
