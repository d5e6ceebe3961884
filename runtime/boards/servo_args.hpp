// What a servo controller accepts as the servos, targets, times, groups and offsets a device
// command names: ids in 0..255 (a byte on the wire) or, with a robot profile, that profile's
// servos and names; positions within the wire's ushort and the profile's range, never 0xff00
// (the wire's "do not move"); whole milliseconds in a ushort; groups 0..254 (255 is the wire's
// "every group"); offsets as ServoOffsetRead can report them (a signed byte). Every parser
// returns the value or an error message that names the field and its range, ready for
// "seqc: error: "; nothing is clamped or wrapped. The CLI adds the exit status (usage).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "compiler/compile.hpp"
#include "runtime/protocol/lsc_messages.hpp"
#include "runtime/protocol/result.hpp"

namespace seqc::boards {

// The servos a `--robot PROFILE` names (xarm, lsc-16, lsc-32, lsc-6); nullopt for "" (no profile:
// servos are plain ids 0..255 and positions plain 0..65535 values).
Result<std::optional<compiler::RobotInfo>> robot_for_profile(const std::string& profile);

// A whole number in decimal; the error names `field`.
Result<long long> parse_integer(std::string_view text, const char* field);

// One servo: an id, or with a profile one of its names ("claw"). With a profile, ids outside
// the profile's servos are refused.
Result<std::uint8_t> parse_servo(std::string_view text,
                                 const std::optional<compiler::RobotInfo>& robot);

// Several servos (at least one, none twice, at most 255 so the count fits its byte).
Result<std::vector<std::uint8_t>> parse_servo_list(const std::vector<std::string>& texts,
                                                   const std::optional<compiler::RobotInfo>& robot);

// The servos a command names (as parse_servo_list), with the --robot profile that names them.
struct ServoSelection {
  std::optional<compiler::RobotInfo> robot;
  std::vector<std::uint8_t> ids;
};
Result<ServoSelection> select_servos(const std::string& profile,
                                     const std::vector<std::string>& texts);

// "ID=POSITION" or "NAME=POSITION"; with a profile the position must lie within its range.
Result<lsc::ServoTarget> parse_target(std::string_view text,
                                      const std::optional<compiler::RobotInfo>& robot);

// The targets of one move, each as parse_target: at most 255 (the count is a byte), no servo
// twice.
Result<std::vector<lsc::ServoTarget>> parse_targets(
    const std::vector<std::string>& texts, const std::optional<compiler::RobotInfo>& robot);

// "500ms" or "1.5s" as whole milliseconds 0..65535 (the protocol's ushort milliseconds).
Result<std::uint16_t> parse_milliseconds(std::string_view text, const char* field);

// A group number for GroupRun/Erase/Speed: 0..254. 255 is the wire's "every group", which
// is asked for with the word `all` where a command allows it, never with a number.
Result<std::uint8_t> parse_group(std::string_view text);

// A servo offset for ServoOffsetAdjust: -128..127. The request carries a short, but
// ServoOffsetRead reports a signed byte, so only that range can be set and read back; larger
// values are refused rather than sent and silently ignored or misreported.
Result<std::int16_t> parse_offset(std::string_view text);

}  // namespace seqc::boards
