#include "compiler/backend/simulate.hpp"

#include <cmath>

#include "compiler/backend/servo_backend.hpp"

namespace seqc::backend {

Simulation simulate(const compiler::ServoProgram& program, std::uint32_t step_ms) {
  Simulation sim;
  const std::vector<std::uint8_t> ids = used_servo_ids(program);
  std::vector<double> pos;
  for (std::uint8_t id : ids) {
    const compiler::ServoInfo* s = program.robot.find_id(id);
    sim.columns.push_back(s != nullptr ? s->name : "servo" + std::to_string(id));
    pos.push_back(s != nullptr ? s->home : 0);
  }
  sim.duration_ms = program.duration_ms();
  auto column_of = [&ids](std::uint8_t id) {
    std::size_t i = 0;
    while (ids[i] != id) ++i;
    return i;
  };

  std::size_t k = 0;
  std::vector<double> from = pos;
  std::uint64_t t = 0;
  for (;;) {
    // Finish every action that has ended by t, so `from` holds where the current one started.
    while (k < program.keyframes.size() &&
           program.keyframes[k].start_ms + std::uint64_t{program.keyframes[k].time_ms} <= t) {
      for (const lsc::ServoTarget& target : program.keyframes[k].targets) {
        from[column_of(target.id)] = target.position;
      }
      ++k;
    }
    Simulation::Sample sample;
    sample.time_ms = static_cast<std::uint32_t>(t);
    std::vector<double> now = from;
    if (k < program.keyframes.size()) {
      const compiler::Keyframe& key = program.keyframes[k];
      const double f = static_cast<double>(t - key.start_ms) / key.time_ms;
      for (const lsc::ServoTarget& target : key.targets) {
        const std::size_t c = column_of(target.id);
        now[c] = from[c] + (target.position - from[c]) * f;
      }
    }
    for (double p : now) sample.positions.push_back(static_cast<int>(std::lround(p)));
    sim.samples.push_back(std::move(sample));
    if (t >= sim.duration_ms) break;
    t = std::min<std::uint64_t>(t + step_ms, sim.duration_ms);
  }
  return sim;
}

std::string to_csv(const Simulation& sim) {
  std::string out = "time_ms";
  for (const std::string& c : sim.columns) out += "," + c;
  out += "\n";
  for (const Simulation::Sample& s : sim.samples) {
    out += std::to_string(s.time_ms);
    for (int p : s.positions) out += "," + std::to_string(p);
    out += "\n";
  }
  return out;
}

}  // namespace seqc::backend
