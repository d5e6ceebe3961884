// `seqc simulate`: each servo's position over time as the controller moves it. The model: an
// action moves every listed servo in a straight line from where it is to its target over the
// action's time, put out as the program's controller model says (the line itself, or rounded or
// truncated to a whole unit); servos start at their home position (the program cannot know
// better).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "compiler/program/program.hpp"

namespace seqc::compiler {

struct Simulation {
  std::vector<std::string> columns;  // servo names, ascending id (servos the program moves)
  struct Sample {
    std::uint32_t time_ms = 0;
    std::vector<int> positions;  // one per column
    // With the intended curve: one per column, NaN while the servo's position is unknown.
    std::vector<double> intended;
    std::array<double, 3> tip{};  // with_tip: the arm's tip in mm (program/arm_kinematics.hpp)
  };
  bool with_intended = false;
  bool with_tip = false;        // the robot has an arm geometry
  std::vector<Sample> samples;  // every step_ms from 0, plus the final instant
  std::uint64_t duration_ms = 0;
};

// step_ms >= 1. `with_intended` adds the intended curve (the program's timeline) per column.
Simulation simulate(const compiler::ServoProgram& program, std::uint32_t step_ms,
                    bool with_intended = false);

// Where the controller has each servo the program moves at `t_ms` (past the end: where the
// last move left it), as simulate()'s sample at that instant says: ascending id, whole units.
// What a robot following a playhead is sent to when it jumps there.
std::vector<lsc::ServoTarget> pose_at(const compiler::ServoProgram& program, std::uint64_t t_ms);

// "time_ms,claw,elbow\n0,500,500\n..."; with the intended curve each servo's column is
// followed by "<name>_intended" (two decimals, empty while unknown); an arm with geometry ends
// each row with "tip_x,tip_y,tip_z" (mm, two decimals).
std::string to_csv(const Simulation& sim);

// Per servo the program moves: the largest distance between the compiled motion and the
// intended curve, checked at every millisecond, and the first instant it happens. The compiled
// motion is the program's controller model (ServoProgram::controller): the straight line from
// target to target, or that line rounded or truncated to a whole unit at every instant.
struct Difference {
  std::string servo;
  double largest = 0;
  std::uint32_t at_ms = 0;
};
std::vector<Difference> compare_with_intent(const compiler::ServoProgram& program);

}  // namespace seqc::compiler
