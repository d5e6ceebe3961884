#include "runtime/boards/xarm_queries.hpp"

#include <sstream>

namespace seqc::boards {

std::optional<std::vector<lsc::ServoTarget>> read_positions(XarmSession& session,
                                                            const std::vector<std::uint8_t>& ids) {
  auto reply = session.ask<lsc::ServoPositions>(lsc::ServoPositionRead{ids}, "the positions");
  if (!reply) return std::nullopt;
  std::vector<lsc::ServoTarget> answered;
  for (std::uint8_t id : ids) {
    for (const lsc::ServoTarget& t : reply->servos) {
      if (t.id == id) {
        answered.push_back(t);
        break;
      }
    }
  }
  return answered;
}

std::vector<std::uint8_t> readable_servos(const compiler::RobotInfo& robot) {
  std::vector<std::uint8_t> ids;
  // A PWM servo's range does not start at 0 (500..2500 us): it has no position to report.
  if (robot.servos.empty() || robot.servos.front().min != 0) return ids;
  for (const compiler::ServoInfo& s : robot.servos) {
    if (robot.highest_defined_id == 0 || s.id <= robot.highest_defined_id) ids.push_back(s.id);
  }
  return ids;
}

std::string led_warning_names(std::uint8_t bits) {
  std::string out;
  for (std::size_t b = 0; b < std::size(kLedWarnings); ++b) {
    if ((bits >> b) & 1) out += (out.empty() ? "" : ",") + std::string(kLedWarnings[b]);
  }
  if ((bits & ~0x07) != 0)
    out += (out.empty() ? "" : ",") + std::string("bits ") + std::to_string(bits);
  return out.empty() ? "none" : out;
}

Result<std::uint8_t> parse_led_warnings(const std::string& text) {
  if (text == "none") return std::uint8_t{0};
  std::uint8_t bits = 0;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    bool found = false;
    for (std::size_t b = 0; b < std::size(kLedWarnings); ++b) {
      if (item == kLedWarnings[b]) {
        bits = static_cast<std::uint8_t>(bits | (1u << b));
        found = true;
      }
    }
    if (!found) {
      return make_error("unknown warning '" + item +
                        "'; use a comma list of overheat, overvoltage, overposition, or none");
    }
  }
  return bits;
}

bool BusServoChanges::complete() const {
  return servo && position_min && position_max && millivolts_min && millivolts_max && temp_max &&
         led_status && led_warning;
}

lsc::BusServoInfoWrite BusServoChanges::applied_to(std::uint8_t id, lsc::BusServoLimits l) const {
  l.position_min = position_min.value_or(l.position_min);
  l.position_max = position_max.value_or(l.position_max);
  l.millivolts_min = millivolts_min.value_or(l.millivolts_min);
  l.millivolts_max = millivolts_max.value_or(l.millivolts_max);
  l.temp_max = temp_max.value_or(l.temp_max);
  l.led_status = led_status.value_or(l.led_status);
  l.led_warning = led_warning.value_or(l.led_warning);
  return lsc::BusServoInfoWrite{servo.value_or(id), l};
}

LimitConflict conflict_in(const lsc::BusServoLimits& l) {
  if (l.position_min > l.position_max) return LimitConflict::Position;
  if (l.millivolts_min > l.millivolts_max) return LimitConflict::Voltage;
  return LimitConflict::None;
}

std::string conflict_text(const lsc::BusServoLimits& l) {
  if (conflict_in(l) == LimitConflict::Position) {
    return "position-min " + std::to_string(l.position_min) + " is above position-max " +
           std::to_string(l.position_max);
  }
  return "millivolts-min " + std::to_string(l.millivolts_min) + " is above millivolts-max " +
         std::to_string(l.millivolts_max);
}

BusServoWrite write_bus_servo_info(XarmSession& session, const BusServoChanges& changes) {
  BusServoWrite out;
  out.write = changes.applied_to(0, {});
  if (!changes.complete()) {
    // Fields not given keep the servo's current values.
    auto info = session.ask<lsc::BusServoInfo>(lsc::BusServoInfoRead{}, "the bus servo info");
    if (!info) return out;
    out.write = changes.applied_to(info->id, info->limits);
  }
  out.conflict = conflict_in(out.write.limits);
  if (out.conflict != LimitConflict::None) return out;
  out.written = session.tell(out.write);
  return out;
}

Result<BusServoChanges> checked_changes(const BusServoFields& o) {
  BusServoChanges c;
  auto u16 = [](const std::optional<long long>& v, const char* field,
                std::optional<std::uint16_t>& out) -> Status {
    if (!v) return Ok{};
    auto r = lsc::checked_u16(*v, field);
    if (!r) return r.error();
    out = *r;
    return Ok{};
  };
  if (o.servo) {
    auto r = lsc::checked_u8(*o.servo, "--servo");
    if (!r) return r.error();
    c.servo = *r;
  }
  for (auto s : {u16(o.position_min, "--position-min", c.position_min),
                 u16(o.position_max, "--position-max", c.position_max),
                 u16(o.millivolts_min, "--millivolts-min", c.millivolts_min),
                 u16(o.millivolts_max, "--millivolts-max", c.millivolts_max),
                 u16(o.temp_max, "--temp-max", c.temp_max)}) {
    if (!s) return s.error();
  }
  if (o.led) c.led_status = *o.led == "on" ? 0 : 1;
  if (o.led_warning) {
    auto w = parse_led_warnings(*o.led_warning);
    if (!w) return make_error("--led-warning: " + w.error().message);
    c.led_warning = *w;
  }
  if (c.complete() && conflict_in(c.applied_to(0, {}).limits) != LimitConflict::None) {
    return make_error(conflict_text(c.applied_to(0, {}).limits));
  }
  return c;
}

}  // namespace seqc::boards
