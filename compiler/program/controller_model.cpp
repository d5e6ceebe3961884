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

}  // namespace seqc::compiler
