#include "compiler/backend/servo_backend.hpp"

#include <set>

namespace seqc::backend {

std::vector<lsc::GroupAction> to_actions(const compiler::ServoProgram& program) {
  std::vector<lsc::GroupAction> actions;
  actions.reserve(program.keyframes.size());
  for (const compiler::Keyframe& k : program.keyframes) {
    actions.push_back(lsc::GroupAction{k.time_ms, k.targets});
  }
  return actions;
}

bool uses_lsc6_dialect(const compiler::ServoProgram& program) {
  return program.robot.profile == "lsc-6";
}

namespace {

Result<std::vector<PlannedFrame>> plan_lsc6(const compiler::ServoProgram& program,
                                            std::uint8_t group) {
  std::vector<lsc6::PlannedAction> actions;
  for (const compiler::Keyframe& k : program.keyframes) {
    lsc6::PlannedAction a{k.time_ms, {}};
    for (const lsc::ServoTarget& t : k.targets) a.servos.push_back({t.id, t.position});
    actions.push_back(std::move(a));
  }
  auto plan = lsc6::plan_download(group, actions);
  if (!plan) return plan.error();
  std::vector<PlannedFrame> out;
  for (std::size_t i = 0; i < plan->size(); ++i) {
    lsc6::Request request{(*plan)[i]};
    auto frame = lsc6::encode(request);
    if (!frame) return frame.error();
    auto serial = lsc::encode_serial(*frame);
    if (!serial) return serial.error();
    out.push_back(PlannedFrame{std::move(request), std::move(*frame), std::move(*serial), i});
  }
  return out;
}

}  // namespace

Result<std::vector<PlannedFrame>> plan_download(const compiler::ServoProgram& program,
                                                std::uint8_t group) {
  if (uses_lsc6_dialect(program)) return plan_lsc6(program, group);
  const std::vector<lsc::GroupAction> actions = to_actions(program);
  auto plan = lsc::plan_group_download(group, actions);
  if (!plan) return plan.error();
  std::vector<PlannedFrame> out;
  out.reserve(plan->size());
  std::size_t next_action = 0;
  for (lsc::Request& request : *plan) {
    auto frame = lsc::encode(request);
    if (!frame) return frame.error();
    auto serial = lsc::encode_serial(*frame);
    if (!serial) return serial.error();
    PlannedFrame p{std::move(request), std::move(*frame), std::move(*serial), std::nullopt};
    if (lsc::group_download_step(std::get<lsc::Request>(p.request)) == 4) {
      p.keyframe = next_action++;
    }
    out.push_back(std::move(p));
  }
  return out;
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

}  // namespace seqc::backend
