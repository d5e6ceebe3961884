// The dance the clock-scaling and --resync tests cut at bar lines: 24 one-beat moves of the base
// at 120 bpm in 4/4, so a beat is 500 ms, a bar 2000 ms, and the dance six bars, 12 s. Both the
// compiler's split at bars and `seqc upload --resync` read this one copy, so their bar lines are
// the same by construction.
#pragma once

namespace seqc::testing {

inline constexpr const char* kSixBarsDance = R"(robot: xarm
tempo: 120
meter: 4/4
sequence:
  - repeat: 12
    do:
      - move: {base: 600}
        time: 1b
      - move: {base: 400}
        time: 1b
)";

}  // namespace seqc::testing
