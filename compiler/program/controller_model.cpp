#include "compiler/program/controller_model.hpp"

#include <cmath>

namespace seqc::compiler {

double controller_output(ControllerModel model, double line) {
  switch (model) {
    case ControllerModel::StraightLine:
      return line;
    case ControllerModel::Rounds:
      return std::floor(line + 0.5);
    case ControllerModel::Truncates:
      return std::trunc(line);
  }
  return line;
}

std::string_view controller_model_name(ControllerModel model) {
  switch (model) {
    case ControllerModel::StraightLine:
      return "straight-line";
    case ControllerModel::Rounds:
      return "rounds";
    case ControllerModel::Truncates:
      return "truncates";
  }
  return "straight-line";
}

std::optional<ControllerModel> controller_model_named(std::string_view name) {
  for (ControllerModel m :
       {ControllerModel::StraightLine, ControllerModel::Rounds, ControllerModel::Truncates}) {
    if (controller_model_name(m) == name) return m;
  }
  return std::nullopt;
}

}  // namespace seqc::compiler
