#include "compiler/formats/car_path.hpp"

#include <cmath>
#include <numbers>

namespace seqc::compiler {

std::vector<CarPose> car_path(const CarSimulation& sim) {
  std::vector<CarPose> out{CarPose{}};
  for (std::size_t i = 1; i < sim.samples.size(); ++i) {
    const double dt = (sim.samples[i].time_ms - sim.samples[i - 1].time_ms) / 1000.0;
    const CarState& s = sim.samples[i - 1].state;
    CarPose p = out.back();
    const double h = p.heading * std::numbers::pi / 180;
    // Body frame (x right, y forward) to the world (x right, y up), heading clockwise.
    p.x += (s.x * std::cos(h) + s.y * std::sin(h)) * dt;
    p.y += (-s.x * std::sin(h) + s.y * std::cos(h)) * dt;
    p.heading += s.z * dt;
    out.push_back(p);
  }
  return out;
}

}  // namespace seqc::compiler
