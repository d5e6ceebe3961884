// The device commands' own option syntax and words: --timeout, and how a servo is named in a
// sentence. What a servo controller accepts as servos, targets, times and groups is the boards
// library's (runtime/boards/servo_args.hpp). Every parser returns the value or an error message
// that names the option, ready for "seqc: error: " and exit status 2 (usage).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "compiler/compile.hpp"
#include "runtime/io/clock.hpp"
#include "base/result.hpp"

namespace seqc::cli {

// A --timeout: "500ms", "2s"; more than 0 and at most one hour.
Result<io::Duration> parse_timeout(std::string_view text);

// "servo 1" or, with a profile, "servo 1 (claw)".
std::string servo_label(std::uint8_t id, const std::optional<compiler::RobotInfo>& robot);
// "servo 1, servo 2 (elbow)".
std::string servo_labels(const std::vector<std::uint8_t>& ids,
                         const std::optional<compiler::RobotInfo>& robot);

}  // namespace seqc::cli
