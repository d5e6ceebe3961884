// One reading per servo (positions, offsets) as the device commands print it: a table with a
// row for every servo asked for, "no answer" where the reply lacks one, then an error naming
// those servos.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "compiler/compile.hpp"
#include "runtime/cli/context.hpp"
#include "runtime/cli/exit_codes.hpp"

namespace seqc::cli {

// The reading for a servo, nullopt if the reply has none.
using ServoReading = std::function<std::optional<std::string>(std::uint8_t id)>;

// Prints the table on ctx.out (columns servo, name with a profile, `column`). Servos without a
// reading give "seqc: error: the controller reported no COLUMN for ..." and DeviceFailure.
ExitCode print_servo_readings(Context& ctx, const std::vector<std::uint8_t>& ids,
                              const std::optional<compiler::RobotInfo>& robot,
                              const std::string& column, const ServoReading& reading);

// The same for a reply's entries (each with an `id`): the reading is the first entry's `field`.
template <class Entry, class Field>
ExitCode print_servo_readings(Context& ctx, const std::vector<std::uint8_t>& ids,
                              const std::optional<compiler::RobotInfo>& robot,
                              const std::string& column, const std::vector<Entry>& entries,
                              Field Entry::*field) {
  return print_servo_readings(ctx, ids, robot, column,
                              [&](std::uint8_t id) -> std::optional<std::string> {
                                for (const Entry& e : entries) {
                                  if (e.id == id) return std::to_string(e.*field);
                                }
                                return std::nullopt;
                              });
}

}  // namespace seqc::cli
