// One servo's target, shared by every servo-controller dialect: a bus id or PWM channel and a
// position in device units (0-1000 on the xArm's bus servos, pulse width in µs on the PWM
// boards). The xArm family's messages and the LSC-6's carry the same pair, so a keyframe's
// targets go to either dialect without conversion.
#pragma once

#include <cstdint>

namespace seqc::lsc {

struct ServoTarget {
  std::uint8_t id = 0;         // bus id, or PWM channel
  std::uint16_t position = 0;  // device units
  friend bool operator==(const ServoTarget&, const ServoTarget&) = default;
};

}  // namespace seqc::lsc
