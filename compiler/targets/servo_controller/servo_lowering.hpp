// Lowers a choreography for a servo-controller robot into keyframes: resolves poses, relative
// moves, mirroring, tempo, easing, repeats and includes; checks limits, speeds, action times
// and the group's action budget (docs/language.md).
#pragma once

#include "compiler/frontend/file_loader.hpp"
#include "compiler/frontend/reporter.hpp"
#include "compiler/frontend/robot_section.hpp"
#include "compiler/program/program.hpp"

namespace seqc::compiler {

// How the timeline is fitted into actions (CompileOptions' fields of the same names).
struct ServoFitting {
  // The timeline is fitted stretched by (1 + clock_ppm / 1e6); the program's timeline stays the
  // author's.
  std::int32_t clock_ppm = 0;
  bool free_end_points = true;  // FitOptions::free_end_points
};

// The program is returned even when errors were reported (the caller decides); keyframes stop
// at the group's 1,020-action budget.
ServoProgram lower_servo_program(const Robot& robot, const LoadedFile& main, FileLoader& loader,
                                 Reporter& reporter, const ServoFitting& fitting = {});

}  // namespace seqc::compiler
