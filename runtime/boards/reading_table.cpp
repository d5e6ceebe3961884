#include "runtime/boards/reading_table.hpp"

#include <algorithm>

#include "runtime/boards/xarm_queries.hpp"

namespace seqc::boards {

std::string Table::render() const {
  std::vector<std::size_t> width;
  for (const auto& row : rows_) {
    if (width.size() < row.size()) width.resize(row.size(), 0);
    for (std::size_t c = 0; c < row.size(); ++c) width[c] = std::max(width[c], row[c].size());
  }
  std::string out;
  for (const auto& row : rows_) {
    std::string line;
    for (std::size_t c = 0; c < row.size(); ++c) {
      const std::string& cell = row[c];
      const std::string pad(width[c] - cell.size(), ' ');
      if (c != 0) line += "  ";
      line += cell + pad;
    }
    while (!line.empty() && line.back() == ' ') line.pop_back();
    out += line + "\n";
  }
  return out;
}

ServoReadings servo_readings(const std::vector<std::uint8_t>& ids,
                             const std::optional<compiler::RobotInfo>& robot,
                             const std::string& column, const ServoReading& reading) {
  Table table(robot ? std::vector<std::string>{"servo", "name", column}
                    : std::vector<std::string>{"servo", column});
  ServoReadings out{column, "", {}};
  for (std::uint8_t id : ids) {
    std::vector<std::string> row{std::to_string(id)};
    if (robot) row.push_back(robot->find_id(id)->name);
    if (auto value = reading(id)) {
      row.push_back(std::move(*value));
    } else {
      out.missing.push_back(id);
      row.push_back("no answer");
    }
    table.add(std::move(row));
  }
  out.table = table.render();
  return out;
}

std::string voltage_text(std::uint16_t millivolts) {
  const unsigned centivolts = (unsigned{millivolts} + 5) / 10;
  const unsigned hundredths = centivolts % 100;
  return std::to_string(millivolts) + " mV (" + std::to_string(centivolts / 100) + "." +
         (hundredths < 10 ? "0" : "") + std::to_string(hundredths) + " V)";
}

std::string bus_servo_limits_table(std::uint8_t id, const lsc::BusServoLimits& l) {
  Table table({"field", "value"});
  table.add({"id", std::to_string(id)});
  table.add({"position-min", std::to_string(l.position_min)});
  table.add({"position-max", std::to_string(l.position_max)});
  table.add({"millivolts-min", std::to_string(l.millivolts_min)});
  table.add({"millivolts-max", std::to_string(l.millivolts_max)});
  table.add({"temp-max", std::to_string(l.temp_max)});
  table.add({"led", l.led_status == 0   ? "on"
                    : l.led_status == 1 ? "off"
                                        : std::to_string(l.led_status)});
  table.add({"led-warning", led_warning_names(l.led_warning)});
  return table.render();
}

std::string bus_servo_state_table(const lsc::BusServoInfo& info) {
  Table now({"state", "value"});
  now.add({"offset", std::to_string(info.offset)});
  now.add({"position", std::to_string(info.position)});
  now.add({"temp", std::to_string(info.temp)});
  now.add({"millivolts", std::to_string(info.millivolts)});
  return now.render();
}

}  // namespace seqc::boards
