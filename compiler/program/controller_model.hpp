// How the controller moves a servo during an action, from its previous target to the new one: a
// property of the board, named by each robot profile (frontend/profiles.cpp) and honoured by the
// fitter (fitting/fitter.hpp), which checks every tolerance against it. docs/language.md says
// which model each built-in profile uses and why.
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

namespace seqc::compiler {

enum class ControllerModel : std::uint8_t {
  StraightLine,  // the exact straight line between the two whole-unit targets
  Rounds,        // that line rounded to the nearest whole unit at every instant
  Truncates,     // that line truncated to a whole unit (towards zero) at every instant
};

// The position the controller puts out when the straight line is at `line`.
double controller_output(ControllerModel model, double line);

// The model's name in a file's `robot: {controller: ...}`: straight-line, rounds, truncates.
std::string_view controller_model_name(ControllerModel model);
std::optional<ControllerModel> controller_model_named(std::string_view name);

}  // namespace seqc::compiler
