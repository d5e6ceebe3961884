// Lowers a choreography for a servo-controller robot into keyframes: resolves poses, relative
// moves, mirroring, tempo, easing, repeats and includes; checks limits, speeds, action times
// and the group's action budget (docs/language.md).
#pragma once

#include "compiler/frontend/file_loader.hpp"
#include "compiler/frontend/reporter.hpp"
#include "compiler/frontend/robot_section.hpp"
#include "compiler/program/program.hpp"

namespace seqc::compiler {

// The program is returned even when errors were reported (the caller decides); keyframes stop
// at the group's 1,020-action budget. With `clock_ppm` the timeline is fitted stretched by
// (1 + clock_ppm / 1e6) (CompileOptions::clock_ppm); the program's timeline stays the author's.
ServoProgram lower_servo_program(const Robot& robot, const LoadedFile& main, FileLoader& loader,
                                 Reporter& reporter, std::int32_t clock_ppm = 0);

}  // namespace seqc::compiler
