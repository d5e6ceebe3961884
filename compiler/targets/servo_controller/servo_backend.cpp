#include "compiler/targets/servo_controller/servo_wire.hpp"

#include <set>

namespace seqc::compiler {

std::vector<lsc::GroupAction> to_actions(const compiler::ServoProgram& program) {
  std::vector<lsc::GroupAction> actions;
  actions.reserve(program.keyframes.size());
  for (const compiler::Keyframe& k : program.keyframes) {
    actions.push_back(lsc::GroupAction{k.time_ms, k.targets});
  }
  return actions;
}

Result<std::vector<PlannedFrame>> plan_lsc6_download(const compiler::ServoProgram& program,
                                                     std::uint8_t group) {
  std::vector<lsc6::PlannedAction> actions;
  for (const compiler::Keyframe& k : program.keyframes) {
    actions.push_back(lsc6::PlannedAction{k.time_ms, k.targets});
  }
  auto plan = lsc6::plan_download(group, actions);
  if (!plan) return plan.error();
  return plan_frames(*plan);
}

Result<std::vector<PlannedFrame>> plan_download(const compiler::ServoProgram& program,
                                                std::uint8_t group) {
  auto plan = lsc::plan_group_download(group, to_actions(program));
  if (!plan) return plan.error();
  return plan_frames(*plan);
}

std::vector<std::uint8_t> used_servo_ids(const compiler::ServoProgram& program) {
  std::set<std::uint8_t> ids;
  for (const compiler::Keyframe& k : program.keyframes) {
    for (const lsc::ServoTarget& t : k.targets) ids.insert(t.id);
  }
  return {ids.begin(), ids.end()};
}

std::vector<TimedMove> live_moves(const compiler::ServoProgram& program) {
  const std::vector<std::uint8_t> ids = used_servo_ids(program);
  std::vector<TimedMove> out;
  out.reserve(program.keyframes.size());
  for (const compiler::Keyframe& k : program.keyframes) {
    TimedMove m;
    m.send_ms = k.start_ms;
    m.move.time_ms = k.time_ms;
    for (std::uint8_t id : ids) {
      lsc::MultiServoMove::Entry e{id, std::nullopt};
      for (const lsc::ServoTarget& t : k.targets) {
        if (t.id == id) e.position = t.position;
      }
      m.move.servos.push_back(e);
    }
    out.push_back(std::move(m));
  }
  return out;
}

std::vector<TimedLsc6Move> live_lsc6_moves(const compiler::ServoProgram& program) {
  std::vector<TimedLsc6Move> out;
  out.reserve(program.keyframes.size());
  for (const compiler::Keyframe& k : program.keyframes) {
    TimedLsc6Move m;
    m.send_ms = k.start_ms;
    m.move.time_ms = k.time_ms;
    m.move.servos = k.targets;
    out.push_back(std::move(m));
  }
  return out;
}

}  // namespace seqc::compiler
