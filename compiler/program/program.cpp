// Lookups on the program types; why they exist is in program.hpp.
#include "compiler/program/program.hpp"

namespace seqc::compiler {

bool servos_report_positions(const RobotInfo& robot) {
  return !robot.servos.empty() && robot.servos.front().min == 0;
}

const ServoInfo* RobotInfo::find_id(std::uint8_t id) const {
  for (const ServoInfo& s : servos) {
    if (s.id == id) return &s;
  }
  return nullptr;
}

const ServoInfo* RobotInfo::find_name(std::string_view name) const {
  for (const ServoInfo& s : servos) {
    if (s.name == name) return &s;
  }
  return nullptr;
}

std::uint64_t ServoProgram::duration_ms() const {
  std::uint64_t total = 0;
  for (const Keyframe& k : keyframes) total += k.time_ms;
  return total;
}

}  // namespace seqc::compiler
