// What a servo controller accepts as the servos, targets, times, groups and offsets a device
// command names: ids in 0..255 (a byte on the wire) or, with a robot profile, that profile's
// servos and names; positions within the profile's range, or without a profile within the range
// every servo controller profile shares (0..2500), so a position no servo can reach is never
// sent; whole milliseconds in a ushort; groups 0..254 (255 is the wire's "every group"); offsets
// as ServoOffsetRead can report them (a signed byte). Every parser returns the value or an error
// message that names the field and its range, ready for "seqc: error: "; nothing is clamped or
// wrapped. The CLI adds the exit status: usage for text that does not parse, invalid input for a
// position outside the range (checked_targets). A device command's --timeout, how long it waits
// for each reply, is parsed here too, in clock time (beats and bars mean nothing to a port).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "base/result.hpp"
#include "compiler/compile.hpp"
#include "protocol/lsc/lsc_messages.hpp"
#include "runtime/io/clock.hpp"

namespace seqc::boards {

// The servos a `--robot PROFILE` names (xarm, bus, lsc-16, lsc-32, lsc-6, learm); nullopt for ""
// (no profile: servos are plain ids 0..255 and positions plain 0..65535 values).
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

// The servos to read: those named (as parse_servo_list), or when none is named every servo of
// `robot`; an error without either.
Result<std::vector<std::uint8_t>> servos_to_read(const std::vector<std::string>& texts,
                                                 const std::optional<compiler::RobotInfo>& robot);

// The servos a command names (as parse_servo_list), with the --robot profile that names them.
struct ServoSelection {
  std::optional<compiler::RobotInfo> robot;
  std::vector<std::uint8_t> ids;
};
Result<ServoSelection> select_servos(const std::string& profile,
                                     const std::vector<std::string>& texts);

// A move target as written: the servo parsed, the position a whole number not yet checked
// against any range (checked_targets does that).
struct RequestedTarget {
  std::uint8_t id = 0;
  long long position = 0;
  friend bool operator==(const RequestedTarget&, const RequestedTarget&) = default;
};

// "ID=POSITION" or "NAME=POSITION": the servo as parse_servo, the position a whole number.
Result<RequestedTarget> parse_target(std::string_view text,
                                     const std::optional<compiler::RobotInfo>& robot);

// The targets of one move, each as parse_target: at most 255 (the count is a byte), no servo
// twice.
Result<std::vector<RequestedTarget>> parse_targets(const std::vector<std::string>& texts,
                                                   const std::optional<compiler::RobotInfo>& robot);

// The positions a servo may be sent: its profile's range, or without a profile the range of
// every servo controller profile together (0..2500).
struct PositionRange {
  long long min = 0;
  long long max = 0;
};
PositionRange position_range(std::uint8_t id, const std::optional<compiler::RobotInfo>& robot);

// The targets as the wire carries them, or an error naming the first servo whose position lies
// outside position_range (its value and the range).
Result<std::vector<lsc::ServoTarget>> checked_targets(
    const std::vector<RequestedTarget>& targets, const std::optional<compiler::RobotInfo>& robot);

// "500ms" or "1.5s" as whole milliseconds 0..65535 (the protocol's ushort milliseconds).
Result<std::uint16_t> parse_milliseconds(std::string_view text, const char* field);

// A group number for GroupRun/Erase/Speed: 0..254. 255 is the wire's "every group", which
// is asked for with the word `all` where a command allows it, never with a number.
Result<std::uint8_t> parse_group(std::string_view text);

// A GROUP argument where every group may be meant: a number as parse_group, or the word `all`
// (the wire's 255, lsc::kAllGroups).
struct GroupTarget {
  std::uint8_t group = 0;
  bool all = false;
};
Result<GroupTarget> parse_group_target(std::string_view text);

// The groups `seqc group erase GROUP|--all` names: GROUP as parse_group_target, or every group
// with `all` set; exactly one of the two must be given.
Result<GroupTarget> erase_target(std::string_view group, bool all);

// GroupRun's play count: `times` (1..65535) unless `forever`, which is the wire's 0; not both
// (`times_given`: --times was on the command line).
Result<std::uint16_t> run_times(long long times, bool times_given, bool forever);

// GroupSpeed's percent: a whole number 1..65535 (100 = as stored); one message for every value
// out of range or not a number.
Result<std::uint16_t> parse_speed_percent(std::string_view text);

// A servo offset for ServoOffsetAdjust: -128..127. The request carries a short, but
// ServoOffsetRead reports a signed byte, so only that range can be set and read back; larger
// values are refused rather than sent and silently ignored or misreported.
Result<std::int16_t> parse_offset(std::string_view text);

// A --timeout: "500ms", "2s"; more than 0 and at most one hour.
Result<io::Duration> parse_timeout(std::string_view text);

}  // namespace seqc::boards
