// How a tip's point reads in a message: "[150mm, 0mm, 80mm]", whole millimetres (servo_tip.cpp,
// servo_tip_line.cpp).
#pragma once

#include <array>
#include <cmath>
#include <string>

#include <fmt/format.h>

namespace seqc::compiler {

inline std::string point_text(const std::array<double, 3>& p) {
  // Adding 0.0 turns a -0 (from rounding a tiny negative) into 0.
  auto mm = [](double v) { return std::round(v) + 0.0; };
  return fmt::format("[{:g}mm, {:g}mm, {:g}mm]", mm(p[0]), mm(p[1]), mm(p[2]));
}

}  // namespace seqc::compiler
