#include "compiler/formats/simulate.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "compiler/program/arm_kinematics.hpp"
#include "compiler/targets/servo_controller/servo_wire.hpp"

namespace seqc::compiler {

namespace {

// The timeline index (robot servo order) of servo `id`.
std::size_t servo_index(const compiler::ServoProgram& program, std::uint8_t id) {
  std::size_t i = 0;
  while (i < program.robot.servos.size() && program.robot.servos[i].id != id) ++i;
  return i;
}

// The controller's motion at whole milliseconds: each action moves its servos in a straight
// line from where they are to their targets (rounded or truncated as the program's controller
// model says); the servos start at home.
class Motion {
 public:
  explicit Motion(const compiler::ServoProgram& p) : p_(p), from_(p.robot.servos.size()) {
    for (std::size_t i = 0; i < from_.size(); ++i) from_[i] = p.robot.servos[i].home;
  }
  // Position of servo index s at t (t non-decreasing between calls).
  double at(std::size_t s, std::uint64_t t) {
    while (k_ < p_.keyframes.size() &&
           p_.keyframes[k_].start_ms + std::uint64_t{p_.keyframes[k_].time_ms} <= t) {
      for (const lsc::ServoTarget& x : p_.keyframes[k_].targets) {
        from_[servo_index(p_, x.id)] = x.position;
      }
      ++k_;
    }
    if (k_ < p_.keyframes.size()) {
      const compiler::Keyframe& key = p_.keyframes[k_];
      for (const lsc::ServoTarget& x : key.targets) {
        if (servo_index(p_, x.id) != s) continue;
        const double f = static_cast<double>(t - key.start_ms) / key.time_ms;
        return compiler::controller_output(p_.controller, from_[s] + (x.position - from_[s]) * f);
      }
    }
    return from_[s];
  }

 private:
  const compiler::ServoProgram& p_;
  std::vector<double> from_;
  std::size_t k_ = 0;
};

// The instants --compare looks at for servo index s: every millisecond between two
// boundaries (an action's start or end, a segment's) up to kCompareExactMs apart, and
// kComparePoints evenly spaced ones where they lie farther apart (a long action or hold, whose
// line and curve are smooth between them), so that a long program costs its actions, not its
// milliseconds.
constexpr std::uint64_t kCompareExactMs = 10'000;
constexpr std::uint64_t kComparePoints = 1'000;
std::vector<std::uint64_t> compare_instants(const compiler::ServoProgram& program, std::size_t s) {
  const std::uint64_t end = program.duration_ms();
  std::vector<std::uint64_t> bounds = {0, end};
  for (const compiler::Keyframe& key : program.keyframes) {
    bounds.push_back(key.start_ms);
    bounds.push_back(key.start_ms + std::uint64_t{key.time_ms});
  }
  if (s < program.timeline.servo_count()) {
    for (std::size_t i = 0; i < program.timeline.count(s); ++i) {
      for (const Instant x : {program.timeline.start_of(s, i), program.timeline.end_of(s, i)}) {
        bounds.push_back(static_cast<std::uint64_t>(std::max<std::int64_t>(0, x.round())));
      }
    }
  }
  std::sort(bounds.begin(), bounds.end());
  bounds.erase(std::unique(bounds.begin(), bounds.end()), bounds.end());
  while (!bounds.empty() && bounds.back() > end) bounds.pop_back();
  std::vector<std::uint64_t> out;
  for (std::size_t i = 0; i + 1 < bounds.size(); ++i) {
    const std::uint64_t a = bounds[i], len = bounds[i + 1] - a;
    const std::uint64_t count = len <= kCompareExactMs ? len : kComparePoints;
    for (std::uint64_t j = 0; j < count; ++j) out.push_back(a + len * j / count);
  }
  out.push_back(end);
  return out;
}

}  // namespace

std::vector<Difference> compare_with_intent(const compiler::ServoProgram& program) {
  std::vector<Difference> out;
  for (std::uint8_t id : used_servo_ids(program)) {
    const std::size_t s = servo_index(program, id);
    Difference d;
    d.servo = program.robot.servos[s].name;
    Motion motion(program);
    for (const std::uint64_t t : compare_instants(program, s)) {
      const auto want = program.timeline.written_value(s, static_cast<double>(t));
      const double got = motion.at(s, t);
      if (!want) continue;
      const double diff = std::abs(got - *want);
      if (diff > d.largest + 1e-9) {
        d.largest = diff;
        d.at_ms = static_cast<std::uint32_t>(t);
      }
    }
    out.push_back(std::move(d));
  }
  return out;
}

std::vector<lsc::ServoTarget> pose_at(const compiler::ServoProgram& program, std::uint64_t t_ms) {
  std::vector<lsc::ServoTarget> out;
  Motion motion(program);
  for (std::uint8_t id : used_servo_ids(program)) {
    const std::size_t s = servo_index(program, id);
    if (s >= program.robot.servos.size()) continue;  // a servo the robot does not name
    const double p = motion.at(s, t_ms);
    out.push_back({id, static_cast<std::uint16_t>(std::lround(p))});
  }
  return out;
}

Simulation simulate(const compiler::ServoProgram& program, std::uint32_t step_ms,
                    bool with_intended) {
  Simulation sim;
  sim.with_intended = with_intended;
  sim.with_tip = program.robot.arm.has_value();
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
    std::vector<double> shown = from;  // what the controller puts out (its model)
    if (k < program.keyframes.size()) {
      const compiler::Keyframe& key = program.keyframes[k];
      const double f = static_cast<double>(t - key.start_ms) / key.time_ms;
      for (const lsc::ServoTarget& target : key.targets) {
        const std::size_t c = column_of(target.id);
        now[c] = from[c] + (target.position - from[c]) * f;
        shown[c] = compiler::controller_output(program.controller, now[c]);
      }
    }
    for (double p : shown) sample.positions.push_back(static_cast<int>(std::lround(p)));
    if (sim.with_tip) {
      // From the unrounded positions; a servo the program never moves stays at home.
      sample.tip = arm_points(*program.robot.arm, [&](std::string_view name) {
                     for (std::size_t c = 0; c < ids.size(); ++c) {
                       if (sim.columns[c] == name) return now[c];
                     }
                     const compiler::ServoInfo* s = program.robot.find_name(name);
                     return s != nullptr ? double(s->home) : 0.0;
                   }).tip;
    }
    if (with_intended) {
      for (std::uint8_t id : ids) {
        const auto want =
            program.timeline.written_value(servo_index(program, id), static_cast<double>(t));
        sample.intended.push_back(want ? *want : std::nan(""));
      }
    }
    sim.samples.push_back(std::move(sample));
    if (t >= sim.duration_ms) break;
    t = std::min<std::uint64_t>(t + step_ms, sim.duration_ms);
  }
  return sim;
}

std::string to_csv(const Simulation& sim) {
  std::string out = "time_ms";
  for (const std::string& c : sim.columns) {
    out += "," + c;
    if (sim.with_intended) out += "," + c + "_intended";
  }
  if (sim.with_tip) out += ",tip_x,tip_y,tip_z";
  out += "\n";
  for (const Simulation::Sample& s : sim.samples) {
    out += std::to_string(s.time_ms);
    for (std::size_t i = 0; i < s.positions.size(); ++i) {
      out += "," + std::to_string(s.positions[i]);
      if (!sim.with_intended) continue;
      out += ",";
      if (!std::isnan(s.intended[i])) {
        char buf[32];
        std::snprintf(buf, sizeof buf, "%.2f", s.intended[i]);
        out += buf;
      }
    }
    for (std::size_t i = 0; sim.with_tip && i < 3; ++i) {
      char buf[32];
      // +0.0 turns a -0.00 (a rounding of a tiny negative) into 0.00.
      std::snprintf(buf, sizeof buf, ",%.2f", std::round(s.tip[i] * 100) / 100 + 0.0);
      out += buf;
    }
    out += "\n";
  }
  return out;
}

}  // namespace seqc::compiler
