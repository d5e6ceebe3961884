#include "compiler/formats/raspblock_simulate.hpp"

#include <algorithm>
#include <type_traits>
#include <variant>

namespace seqc::compiler {
namespace {

std::string cell(const std::optional<int>& v) { return v ? std::to_string(*v) : std::string(); }

}  // namespace

void apply_packet(CarState& s, const raspblock::Packet& packet) {
  std::visit(
      [&s](const auto& p) {
        using T = std::decay_t<decltype(p)>;
        if constexpr (std::is_same_v<T, raspblock::Rocker>) {
          s.x = p.x;
          s.y = p.y;
          s.z = p.z;
        } else if constexpr (std::is_same_v<T, raspblock::GimbalServos>) {
          s.pan = p.horizontal;
          s.tilt = p.vertical;
        } else if constexpr (std::is_same_v<T, raspblock::SingleServo>) {
          if (p.index >= 1 && p.index <= s.servos.size()) s.servos[p.index - 1] = p.position;
        }
        // PID settings change how the board drives, not where it is.
      },
      packet);
}

CarSimulation simulate_car(const compiler::RaspblockProgram& program, std::uint32_t step_ms) {
  CarSimulation sim;
  sim.duration_ms = program.duration_ms;
  CarState state;
  std::size_t next = 0;
  std::uint32_t t = 0;
  for (;;) {
    while (next < program.packets.size() && program.packets[next].at_ms <= t) {
      apply_packet(state, program.packets[next].packet);
      ++next;
    }
    sim.samples.push_back({t, state});
    if (t >= sim.duration_ms) break;
    t = std::min(t + step_ms, sim.duration_ms);
  }
  return sim;
}

CarSimulation car_changes(const compiler::RaspblockProgram& program) {
  CarSimulation sim;
  sim.duration_ms = program.duration_ms;
  CarState state;
  std::size_t next = 0;
  std::uint32_t t = 0;
  for (;;) {
    while (next < program.packets.size() && program.packets[next].at_ms <= t) {
      apply_packet(state, program.packets[next].packet);
      ++next;
    }
    sim.samples.push_back({t, state});
    if (next == program.packets.size() || program.packets[next].at_ms > sim.duration_ms) break;
    t = program.packets[next].at_ms;
  }
  return sim;
}

std::uint32_t car_picture_step_ms(const compiler::RaspblockProgram& program) {
  const std::uint32_t step = (program.duration_ms + kCarPictureSamples - 1) / kCarPictureSamples;
  return std::max<std::uint32_t>(20, step);
}

std::string to_csv(const CarSimulation& sim) {
  std::string out = "time_ms,x,y,z,pan,tilt,servo1,servo2,servo3,servo4\n";
  for (const CarSimulation::Sample& s : sim.samples) {
    const CarState& c = s.state;
    out += std::to_string(s.time_ms) + "," + std::to_string(c.x) + "," + std::to_string(c.y) + "," +
           std::to_string(c.z) + "," + cell(c.pan) + "," + cell(c.tilt);
    for (const auto& servo : c.servos) out += "," + cell(servo);
    out += "\n";
  }
  return out;
}

}  // namespace seqc::compiler
