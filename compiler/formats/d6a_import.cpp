#include "compiler/formats/d6a_import.hpp"

#include <filesystem>

#include <fmt/format.h>

#include "compiler/frontend/profiles.hpp"
#include "protocol/lsc/group_download.hpp"

namespace seqc::compiler {

ImportOptions import_options_for(const std::string& path, const std::string& stdin_name,
                                 const std::string& profile) {
  if (path == "-") return {"imported", stdin_name, profile};
  const std::filesystem::path file(path);
  return {file.stem().string(), file.filename().string(), profile};
}

Result<std::string> choreography_from_d6a(const compiler::D6aTable& table,
                                          const ImportOptions& options) {
  const std::string profile_name =
      !options.profile.empty() ? options.profile : (table.servo_columns == 6 ? "xarm" : "bus");
  const RobotProfile* profile = find_profile(profile_name);
  if (profile == nullptr || profile->kind != RobotKind::ServoController) {
    return make_error("--robot " + profile_name + ": not a servo controller profile (" +
                      profile_list() + ")");
  }
  const RobotInfo robot = robot_from_profile(*profile);
  std::vector<std::string> names(table.servo_columns + 1);
  for (std::size_t k = 1; k <= table.servo_columns; ++k) {
    const ServoInfo* s = robot.find_id(static_cast<std::uint8_t>(k));
    if (s == nullptr) {
      return make_error("Servo" + std::to_string(k) + ": " + profile_name + " has no servo id " +
                        std::to_string(k) + " (ids " + std::to_string(profile->first_id) + "-" +
                        std::to_string(profile->last_id) + ")");
    }
    names[k] = s->name;
  }
  if (table.rows.empty()) return make_error("the ActionGroup table has no rows");

  std::string out = fmt::format(
      "# Imported by seqc from {}: one step per row of its ActionGroup table ({} rows, "
      "Servo1..Servo{}).\n"
      "name: {}\n",
      options.source, table.rows.size(), table.servo_columns, options.name);
  if (profile_name == "bus") {
    // Name exactly the servos the file has, so that `seqc export` writes the same columns.
    out += "robot:\n  profile: bus\n  servos: {";
    for (std::size_t k = 1; k <= table.servo_columns; ++k) {
      out += fmt::format("{}{}: {}", k == 1 ? "" : ", ", names[k], k);
    }
    out += "}\n";
  } else {
    out += "robot: " + profile_name + "\n";
  }
  out += "sequence:\n";
  std::vector<int> previous;
  for (std::size_t r = 0; r < table.rows.size(); ++r) {
    const compiler::D6aRow& row = table.rows[r];
    const std::string where = fmt::format("row {} (Index {})", r + 1, row.index);
    if (row.time_ms < static_cast<int>(lsc::kMinActionMs) ||
        row.time_ms > static_cast<int>(lsc::kMaxActionMs)) {
      return make_error(
          fmt::format("{}: Time {} ms is outside the controller's {}-{} ms per "
                      "action",
                      where, row.time_ms, lsc::kMinActionMs, lsc::kMaxActionMs));
    }
    std::string moves;
    for (std::size_t k = 1; k <= table.servo_columns; ++k) {
      const int p = row.positions[k - 1];
      if (p < profile->min || p > profile->max) {
        return make_error(fmt::format("{}: Servo{} is {}, outside {}'s {}-{}", where, k, p,
                                      profile_name, profile->min, profile->max));
      }
      if (!previous.empty() && previous[k - 1] == p) continue;
      moves += fmt::format("{}{}: {}", moves.empty() ? "" : ", ", names[k], p);
    }
    if (moves.empty()) {
      out += fmt::format("  - wait: {}ms              # row {}\n", row.time_ms, r + 1);
    } else {
      out += fmt::format("  - move: {{{}}}  # row {}\n    time: {}ms\n", moves, r + 1, row.time_ms);
    }
    previous = row.positions;
  }
  return out;
}

}  // namespace seqc::compiler
