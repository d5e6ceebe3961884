#include "runtime/cli/servo_readings.hpp"

#include <ostream>
#include <utility>

#include "runtime/cli/device_args.hpp"
#include "runtime/cli/device_table.hpp"

namespace seqc::cli {

ExitCode print_servo_readings(Context& ctx, const std::vector<std::uint8_t>& ids,
                              const std::optional<compiler::RobotInfo>& robot,
                              const std::string& column, const ServoReading& reading) {
  Table table(robot ? std::vector<std::string>{"servo", "name", column}
                    : std::vector<std::string>{"servo", column});
  std::vector<std::uint8_t> missing;
  for (std::uint8_t id : ids) {
    std::vector<std::string> row{std::to_string(id)};
    if (robot) row.push_back(robot->find_id(id)->name);
    if (auto value = reading(id)) {
      row.push_back(std::move(*value));
    } else {
      missing.push_back(id);
      row.push_back("no answer");
    }
    table.add(std::move(row));
  }
  ctx.out << table.render();
  if (!missing.empty()) {
    ctx.err << "seqc: error: the controller reported no " << column << " for "
            << servo_labels(missing, robot) << " (not on the bus, or not answering)\n";
    return ExitCode::DeviceFailure;
  }
  return ExitCode::Ok;
}

}  // namespace seqc::cli
