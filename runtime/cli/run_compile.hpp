// Compiling a file for a run that starts on the robot now (`upload --run`, `play`): a servo
// whose first move is relative to where the robot stands (`move: {base: +100}` before any
// absolute move of 'base') is read over the port first and the file compiled from the
// readings (compiler::RobotStart), so the limits are checked against where the move really
// ends. A file without such a move compiles once, as compile_and_report compiles it.
#pragma once

#include <string>

#include "runtime/cli/clock_option.hpp"
#include "runtime/cli/compile_report.hpp"
#include "runtime/cli/context.hpp"

namespace seqc::cli {

// Compiles `path` and prints its diagnostics (compile_and_report); where a first move needs a
// reading, opens `port` (as the run will), reads the servos it names and compiles again from
// them. A port that does not open or a read that is not answered ends it: code is then the
// port's failure or DeviceFailure, said on stderr, and nothing is compiled.
Compiled compile_for_run(Context& ctx, const std::string& path, bool strict,
                         const std::string& port, const ClockScaleOptions* clock = nullptr);

}  // namespace seqc::cli
