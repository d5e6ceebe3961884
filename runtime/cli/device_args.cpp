#include "runtime/cli/device_args.hpp"

#include <string>

#include "base/terminal_text.hpp"

namespace seqc::cli {

std::string servo_label(std::uint8_t id, const std::optional<compiler::RobotInfo>& robot) {
  std::string out = "servo " + std::to_string(id);
  if (robot) {
    if (const compiler::ServoInfo* s = robot->find_id(id))
      out += " (" + terminal_safe(s->name) + ")";
  }
  return out;
}

std::string servo_labels(const std::vector<std::uint8_t>& ids,
                         const std::optional<compiler::RobotInfo>& robot) {
  std::string out;
  for (std::uint8_t id : ids) out += (out.empty() ? "" : ", ") + servo_label(id, robot);
  return out;
}

}  // namespace seqc::cli
