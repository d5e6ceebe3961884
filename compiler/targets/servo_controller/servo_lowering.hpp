// The servo-controller target, as two stages the driver (compiler/compile.cpp) runs on either
// side of fitting:
//
// - walk_servo_file() lowers a choreography's steps to the timeline (docs/language.md): poses,
//   relative moves, mirroring, tempo, easing, repeats and includes, with the checks of limits,
//   speeds, action times and a lower bound of the actions the group needs;
// - servo_program() turns the actions fitting made of that timeline into the program: the
//   group's capacity checked, each curve's shortfall warned once, the keyframes with the
//   controller's servo ids, and the tip's own error along every `path: line` move.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "compiler/fitting/fitter.hpp"
#include "compiler/frontend/file_loader.hpp"
#include "compiler/frontend/reporter.hpp"
#include "compiler/frontend/robot_section.hpp"
#include "compiler/frontend/step_walk.hpp"
#include "compiler/program/program.hpp"
#include "compiler/targets/servo_controller/tip_line.hpp"

namespace seqc::compiler {

// A `path: line` move as the walk left it: what the tip's error is measured against.
struct ServoTipLine {
  compiler::TipLineRequest request;
  std::array<std::size_t, 4> joints{};  // base, shoulder, elbow and wrist servos
  Location path_at;
};

// What the walk leaves for fitting.
struct ServoWalk {
  Timeline timeline;  // what the author meant, per servo, on exact time
  // A lower bound of the actions (each step needs at least its count), and whether repeats
  // stopped expanding once it passed the group's capacity.
  std::uint64_t min_actions = 0;
  bool truncated = false;
  // The step that made the count pass the capacity (the walk stopped there and the file is not
  // fitted), and the performances and includes that led to it.
  std::optional<Location> over_budget_at;
  std::vector<Reporter::Note> over_budget_notes;
  std::optional<Location> sequence_at;  // the main file's `sequence:`
  std::vector<ServoTipLine> lines;      // every `path: line` move, in the order walked
  std::size_t capacity = 0;             // actions one group holds on the robot's controller
  // Groups the dance may take, one after another (compiler/targets/servo_controller/chain.hpp):
  // the walk's budget is capacity x groups.
  std::size_t groups = 1;
  std::optional<ExactMs> over_budget_time;  // when the step at over_budget_at starts
  // What performed when (repeat passes, section performances, includes), for an error about an
  // action found only once fitted.
  StepWalker::Performances performances;
  // The ids of the servos whose first move is relative to where the robot stands, in the order
  // walked.
  std::vector<std::uint8_t> start_reads;
};

// The walk of `main` (and what it includes). Errors go to `reporter`; the walk is returned
// whatever they are.
// `groups`: how many consecutive groups the dance may take (1: the classic one group).
// `times`, when given, gets when each step ran (step_times.hpp).
ServoWalk walk_servo_file(const Robot& robot, const LoadedFile& main, FileLoader& loader,
                          Reporter& reporter, std::size_t groups = 1, const RobotStart& start = {},
                          StepTimes* times = nullptr);

// The servo controllers' steps: their verbs and every key a step may have.
const StepTable& servo_step_table();

// Whether the walk goes on to fitting: not after errors (fitting a file with mistakes would
// only cost time: a long, slow curve took seconds), nor when the walk alone already needs more
// actions than a group holds (reported here, where the walk stopped, with the performances and
// includes that led there as notes).
bool ready_to_fit(const ServoWalk& walk, const Robot& robot, Reporter& reporter);

// How fitting treats this robot's servos: its controller's model and each servo's limits.
FitOptions servo_fit_options(const Robot& robot, bool free_end_points);

// The program from the walk and its fitted actions (fitted with servo_fit_options() on a board
// `clock_ppm` fast). Keyframes stop at the capacity of the walk's groups, which is an error
// naming the bar and time of the first action that does not fit.
ServoProgram servo_program(const Robot& robot, ServoWalk walk, const FitResult& fit,
                           std::int32_t clock_ppm, Reporter& reporter);

}  // namespace seqc::compiler
