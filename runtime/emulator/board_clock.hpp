// A board's own oscillator, as the emulators model it: a clock `ppm` parts per million fast
// runs a stored group's action times that much quicker in host time (+0.8 % = +8000 ppm: a
// 1000 ms action lasts 1000 / 1.008 ms). Integer arithmetic only, so the same setting always
// gives the same nanoseconds on every platform.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "base/result.hpp"
#include "runtime/io/clock.hpp"

namespace seqc::emu {

// The largest error the emulators take, either way: 20 % (an RC oscillator is within a few).
inline constexpr std::int32_t kMaxClockPpm = 200000;

// "+0.8%", "-1%", "+120ppm", "0" (sign optional; % takes up to four decimals, ppm none).
// The error names what is wrong.
Result<std::int32_t> parse_clock_error(std::string_view text);

// "+8000ppm", "-10000ppm", "0ppm": the form parse_clock_error takes back.
std::string format_clock_error(std::int32_t ppm);

// The host time `board` lasts on a board whose clock is `ppm` fast (slow when negative):
// board x 1e6 / (1e6 + ppm), to the nearest nanosecond below.
io::Duration board_to_host(io::Duration board, std::int32_t ppm);

}  // namespace seqc::emu
