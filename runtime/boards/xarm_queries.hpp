// The xArm family's readings and settings that take more than one request, over an
// XarmSession (xarm_session.hpp): servo positions matched to the servos asked for (and which
// servos can report one), and a bus servo's limits (BusServoInfoRead/Write). BusServoInfoWrite is
// not addressed: every servo on the bus takes what it carries (docs/protocol/servo-controller.md),
// so a write that changes only some fields reads the attached servo first and keeps its other
// values. Like the session, these return data and status values; a failed exchange is the session's
// failure().
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "base/result.hpp"
#include "compiler/compile.hpp"
#include "protocol/lsc/lsc_messages.hpp"
#include "runtime/boards/xarm_session.hpp"

namespace seqc::boards {

// ServoPositionRead for `ids`: the servos that answered, in the order of `ids`, each once;
// nullopt when the exchange failed.
std::optional<std::vector<lsc::ServoTarget>> read_positions(XarmSession& session,
                                                            const std::vector<std::uint8_t>& ids);

// The servos of `robot` whose positions can be read back: those up to the highest its robot
// section defines (all of the profile's when it defines none); none when they are PWM servos,
// which cannot report where they are.
std::vector<std::uint8_t> readable_servos(const compiler::RobotInfo& robot);

// The names of BusServoLimits::led_warning's bits, in bit order.
inline constexpr std::string_view kLedWarnings[] = {"overheat", "overvoltage", "overposition"};
// "overheat,overposition"; bits above the three as "bits N"; "none" for 0.
std::string led_warning_names(std::uint8_t bits);
// The inverse: a comma list of kLedWarnings names, or "none". The error names the unknown one.
Result<std::uint8_t> parse_led_warnings(const std::string& text);

// The fields a bus-servo write sets; those left empty keep the servo's current values.
struct BusServoChanges {
  std::optional<std::uint8_t> servo;
  std::optional<std::uint16_t> position_min, position_max, millivolts_min, millivolts_max, temp_max;
  std::optional<std::uint8_t> led_status, led_warning;

  bool complete() const;
  // The write these changes make to a servo whose id and limits are `id` and `current`.
  lsc::BusServoInfoWrite applied_to(std::uint8_t id, lsc::BusServoLimits current) const;
};

// The fields of a BusServoInfoWrite as the user gives them (`seqc bus-info write --servo ...`):
// whole numbers not yet checked, the LED "on" or "off", the warnings as parse_led_warnings reads
// them; unset fields are not given.
struct BusServoFields {
  std::optional<long long> servo, position_min, position_max, millivolts_min, millivolts_max,
      temp_max;
  std::optional<std::string> led, led_warning;
};
// Limits no servo can hold: a lowest value above the highest.
enum class LimitConflict { None, Position, Voltage };
LimitConflict conflict_in(const lsc::BusServoLimits& limits);
// The first conflict of `limits` in words: "position-min 600 is above position-max 400".
std::string conflict_text(const lsc::BusServoLimits& limits);

// The changes the fields make, each checked against its wire width; the error names the first
// field out of range as its option (--position-min), ready for "seqc: error: ". When every field
// is given, limits that conflict are refused too (conflict_text), before any servo is read.
Result<BusServoChanges> checked_changes(const BusServoFields& fields);

struct BusServoWrite {
  bool written = false;  // sent and confirmed
  lsc::BusServoInfoWrite write;
  // Not None: the merged limits conflict, and nothing was written.
  LimitConflict conflict = LimitConflict::None;
};
// Reads the attached servo when `changes` is not complete, merges, and writes unless the result
// conflicts. written is false after a conflict or a failed exchange (session.failure()).
BusServoWrite write_bus_servo_info(XarmSession& session, const BusServoChanges& changes);

}  // namespace seqc::boards
