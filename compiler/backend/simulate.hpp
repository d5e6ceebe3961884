// `seqc simulate`: each servo's position over time as the controller moves it. The model: an
// action moves every listed servo in a straight line from where it is to its target over the
// action's time; servos start at their home position (the program cannot know better).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "compiler/compile.hpp"

namespace seqc::backend {

struct Simulation {
  std::vector<std::string> columns;  // servo names, ascending id (servos the program moves)
  struct Sample {
    std::uint32_t time_ms = 0;
    std::vector<int> positions;  // one per column
  };
  std::vector<Sample> samples;  // every step_ms from 0, plus the final instant
  std::uint64_t duration_ms = 0;
};

// step_ms >= 1.
Simulation simulate(const compiler::ServoProgram& program, std::uint32_t step_ms);

// "time_ms,claw,elbow\n0,500,500\n...".
std::string to_csv(const Simulation& sim);

}  // namespace seqc::backend
