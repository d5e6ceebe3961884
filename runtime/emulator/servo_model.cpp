#include "runtime/emulator/servo_model.hpp"

#include <algorithm>

namespace seqc::emu {

ServoBank::ServoBank(const ServoModelConfig& config) {
  Servo s;
  s.from = s.to = config.home;
  s.limits.position_min = config.min;
  s.limits.position_max = config.max;
  servos_.assign(config.count, s);
  for (std::size_t i = 0; i < servos_.size(); ++i) servos_[i].id = static_cast<std::uint8_t>(i + 1);
  for (const auto& [id, position] : config.initial) {
    if (id >= 1 && id <= servos_.size()) servos_[id - 1].from = servos_[id - 1].to = position;
  }
}

bool ServoBank::has(std::uint8_t id) const { return find(id) != nullptr; }

std::vector<std::uint8_t> ServoBank::ids() const {
  std::vector<std::uint8_t> out;
  for (const Servo& s : servos_) out.push_back(s.id);
  return out;
}

const ServoBank::Servo* ServoBank::find(std::uint8_t id) const {
  for (const Servo& s : servos_) {
    if (s.id == id) return &s;
  }
  return nullptr;
}
ServoBank::Servo* ServoBank::find(std::uint8_t id) {
  for (Servo& s : servos_) {
    if (s.id == id) return &s;
  }
  return nullptr;
}

std::uint16_t ServoBank::at_time(const Servo& s, io::TimePoint at) {
  if (at >= s.t1 || s.t1 <= s.t0) return s.to;
  if (at <= s.t0) return s.from;
  const auto span = (s.t1 - s.t0).count();
  const auto done = (at - s.t0).count();
  const auto delta = static_cast<long double>(s.to) - static_cast<long double>(s.from);
  const long double p = static_cast<long double>(s.from) +
                        delta * static_cast<long double>(done) / static_cast<long double>(span);
  return static_cast<std::uint16_t>(p + 0.5L);
}

void ServoBank::move(std::uint8_t id, std::uint16_t target, io::Duration duration,
                     io::TimePoint start) {
  for_each(id, [&](Servo& s) {
    const std::uint16_t here = at_time(s, start);
    s.from = here;
    s.to = std::clamp(target, s.limits.position_min, s.limits.position_max);
    s.t0 = start;
    s.t1 = start + std::max(duration, io::Duration{0});
    s.powered = true;
  });
}

void ServoBank::power_off(std::uint8_t id, io::TimePoint at) {
  for_each(id, [&](Servo& s) {
    const std::uint16_t here = at_time(s, at);
    s.from = s.to = here;
    s.t0 = s.t1 = at;
    s.powered = false;
  });
}

bool ServoBank::pose_by_hand(std::uint8_t id, std::uint16_t position, io::TimePoint at) {
  Servo* s = find(id);
  if (s == nullptr || s->powered) return false;
  s->from = s->to = position;
  s->t0 = s->t1 = at;
  return true;
}

bool ServoBank::powered(std::uint8_t id) const {
  const Servo* s = find(id);
  return s && s->powered;
}

std::uint16_t ServoBank::position(std::uint8_t id, io::TimePoint at) const {
  const Servo* s = find(id);
  return s ? at_time(*s, at) : 0;
}

void ServoBank::adjust_offset(std::uint8_t id, std::int8_t offset) {
  for_each(id, [&](Servo& s) { s.offset = offset; });
}
void ServoBank::write_offset(std::uint8_t id) {
  for_each(id, [&](Servo& s) { s.stored_offset = s.offset; });
}
std::int8_t ServoBank::offset(std::uint8_t id) const {
  const Servo* s = find(id);
  return s ? s->offset : std::int8_t{0};
}
std::int8_t ServoBank::stored_offset(std::uint8_t id) const {
  const Servo* s = find(id);
  return s ? s->stored_offset : std::int8_t{0};
}

void ServoBank::set_mode(std::uint8_t id, lsc::ServoMode mode, std::uint16_t milliseconds) {
  for_each(id, [&](Servo& s) {
    s.mode = mode;
    s.mode_ms = milliseconds;
  });
}
lsc::ServoMode ServoBank::mode(std::uint8_t id) const {
  const Servo* s = find(id);
  return s ? s->mode : lsc::ServoMode::Servo;
}
std::uint16_t ServoBank::mode_milliseconds(std::uint8_t id) const {
  const Servo* s = find(id);
  return s ? s->mode_ms : std::uint16_t{0};
}

void ServoBank::write_limits(const lsc::BusServoLimits& limits) {
  for (auto& s : servos_) s.limits = limits;
}
void ServoBank::write_id(std::uint8_t id) {
  if (id > kMaxServoId) return;
  for (auto& s : servos_) s.id = id;
}
lsc::BusServoLimits ServoBank::limits(std::uint8_t id) const {
  const Servo* s = find(id);
  return s ? s->limits : lsc::BusServoLimits{};
}

void ServoBank::power_cycle(io::TimePoint at) {
  for (auto& s : servos_) {
    const std::uint16_t here = at_time(s, at);
    s.from = s.to = here;
    s.t0 = s.t1 = at;
    s.powered = true;
    s.offset = s.stored_offset;
    s.mode = lsc::ServoMode::Servo;
    s.mode_ms = 0;
  }
}

}  // namespace seqc::emu
