// `seqc simulate` for the Raspblock car: the state the board is driven to over time.
//
// The board applies each packet when it arrives and has no notion of duration, so the state
// at time t is what the packets sent at or before t set. Fields no packet has set yet are
// unknown (empty in the CSV): seqc cannot know where the gimbal was before the play.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "compiler/program/raspblock_program.hpp"

namespace seqc::compiler {

struct CarState {
  int x = 0, y = 0, z = 0;  // rocker speeds (0 until driven)
  std::optional<int> pan, tilt;
  std::array<std::optional<int>, 4> servos;  // single servos 1..4
  friend bool operator==(const CarState&, const CarState&) = default;
};

// The car's state after the board takes `packet` (a PID setting changes how it drives, not
// where it is). Shared by the simulation and by whatever follows a car's program live.
void apply_packet(CarState& s, const raspblock::Packet& packet);

struct CarSimulation {
  struct Sample {
    std::uint32_t time_ms = 0;
    CarState state;
  };
  std::vector<Sample> samples;  // every step_ms from 0, plus the final instant
  std::uint32_t duration_ms = 0;
};

// step_ms >= 1.
CarSimulation simulate_car(const compiler::RaspblockProgram& program, std::uint32_t step_ms);

// The same state only where it can change: at 0 and at each packet's instant up to the end, so
// what simulate_car(program, 1) says at every millisecond is the last of these at or before it,
// at the cost of the packets rather than the milliseconds.
CarSimulation car_changes(const compiler::RaspblockProgram& program);

// The step of the car's pictures (`seqc plot`'s lanes and path, the preview's path): 20 ms, or
// coarser for a long program so that they hold at most kCarPictureSamples samples.
constexpr std::uint32_t kCarPictureSamples = 10'000;
std::uint32_t car_picture_step_ms(const compiler::RaspblockProgram& program);

// "time_ms,x,y,z,pan,tilt,servo1,servo2,servo3,servo4\n0,0,0,0,1500,1500,,,,\n...".
std::string to_csv(const CarSimulation& sim);

}  // namespace seqc::compiler
