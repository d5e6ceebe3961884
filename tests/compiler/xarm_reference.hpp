// What the tip tests share about the xArm, written from the documents rather than taken from
// the compiler: its degrees per unit, and the distance between two points in mm.
#pragma once

#include <array>
#include <cmath>

namespace seqc::compiler::testing {

// The xArm profile: 1000 units over 240 degrees.
inline constexpr double kDegPerUnit = 0.24;

inline double distance(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  return std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
}

}  // namespace seqc::compiler::testing
