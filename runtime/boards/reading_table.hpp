// Device readings as they are printed: plain text tables (a header row, left-aligned columns two
// spaces apart, no trailing spaces) of one reading per servo asked for (positions, offsets), with
// "no answer" where the reply lacks one and those servos listed for the caller's error; a bus
// servo's limits and state; the supply voltage. Only the layout is here; the sentence around a
// missing reading is the CLI's.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "compiler/compile.hpp"
#include "protocol/lsc/lsc_messages.hpp"

namespace seqc::boards {

class Table {
 public:
  explicit Table(std::vector<std::string> header) : rows_{std::move(header)} {}
  void add(std::vector<std::string> row) { rows_.push_back(std::move(row)); }
  std::string render() const;

 private:
  std::vector<std::vector<std::string>> rows_;
};

// A table of one reading per servo: columns servo, name (with a profile), `column`.
struct ServoReadings {
  std::string column;                 // "position", "offset"
  std::string table;                  // a row for every servo asked for, in order
  std::vector<std::uint8_t> missing;  // the servos the reply has no reading for
};

// The reading for a servo, nullopt if the reply has none.
using ServoReading = std::function<std::optional<std::string>(std::uint8_t id)>;
ServoReadings servo_readings(const std::vector<std::uint8_t>& ids,
                             const std::optional<compiler::RobotInfo>& robot,
                             const std::string& column, const ServoReading& reading);

// The same for a reply's entries (each with an `id`): the reading is the first entry's `field`.
template <class Entry, class Field>
ServoReadings servo_readings(const std::vector<std::uint8_t>& ids,
                             const std::optional<compiler::RobotInfo>& robot,
                             const std::string& column, const std::vector<Entry>& entries,
                             Field Entry::*field) {
  return servo_readings(ids, robot, column, [&](std::uint8_t id) -> std::optional<std::string> {
    for (const Entry& e : entries) {
      if (e.id == id) return std::to_string(e.*field);
    }
    return std::nullopt;
  });
}

// A supply voltage as `seqc battery` prints it: "7500 mV (7.50 V)", the volts rounded to the
// nearest 10 mV.
std::string voltage_text(std::uint16_t millivolts);

// A bus servo's limits as `field value` rows, after the id row: position-min ... led-warning.
std::string bus_servo_limits_table(std::uint8_t id, const lsc::BusServoLimits& limits);
// Its state as `state value` rows: offset, position, temp, millivolts.
std::string bus_servo_state_table(const lsc::BusServoInfo& info);

}  // namespace seqc::boards
