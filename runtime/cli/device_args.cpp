#include "runtime/cli/device_args.hpp"

#include <string>

#include "base/terminal_text.hpp"
#include "base/units.hpp"

namespace seqc::cli {

Result<io::Duration> parse_timeout(std::string_view text) {
  // A reply is waited for in clock time: the language's beats and bars mean nothing here, so
  // the parse's own message, which offers them, is not passed on (but its hint for a number
  // without a unit is).
  auto time = seqc::parse_time(text);
  if (!time && time.error().message.find("has no unit") != std::string::npos) {
    return make_error("--timeout: " + time.error().message);
  }
  if (!time || time->unit == seqc::TimeUnit::Beats || time->unit == seqc::TimeUnit::Bars) {
    return make_error("--timeout: '" + std::string(text) +
                      "' is not a time in ms or s; write it like '500ms' or '2s'");
  }
  const double ms = time->unit == seqc::TimeUnit::Seconds ? time->amount * 1000 : time->amount;
  if (ms <= 0 || ms > 3600.0 * 1000) {
    return make_error("--timeout must be more than 0 and at most 1 hour, got '" +
                      std::string(text) + "'");
  }
  return std::chrono::duration_cast<io::Duration>(std::chrono::duration<double, std::milli>(ms));
}

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
