// Lowers a choreography for the Raspblock car board (`robot: raspblock`, docs/raspblock.md)
// into a timed packet stream: drives, gimbal and servo moves interpolated at the file's
// resolution, waits, and the PID settings sent first, with the structure and musical time
// every robot kind shares (repeat, include, sections, together, at, tempo, meter;
// step_walk.hpp). Checks every range, every key (with "did you mean"), and that the stream
// fits the 115200-baud link.
#pragma once

#include <cstdint>

#include "compiler/frontend/file_loader.hpp"
#include "compiler/frontend/reporter.hpp"
#include "compiler/frontend/robot_section.hpp"
#include "compiler/frontend/step_times.hpp"
#include "compiler/program/raspblock_program.hpp"

namespace seqc::compiler {

// Decision: moves are split into one packet per 20 ms (50 per second) unless the file sets
// `resolution` or a move sets `steps`: the rate hobby servos are refreshed at.
inline constexpr std::uint32_t kRaspblockDefaultResolutionMs = 20;
// Limits that keep a runaway repeat from exhausting memory.
inline constexpr std::uint64_t kRaspblockMaxStreamMs = 24ull * 3600 * 1000;
inline constexpr std::size_t kRaspblockMaxPackets = 1'000'000;

// The program is returned even when errors were reported (the caller decides). `times`, when
// given, gets when each step ran (compiler/frontend/step_times.hpp).
RaspblockProgram lower_raspblock_program(const Robot& robot, const LoadedFile& main,
                                         FileLoader& loader, Reporter& reporter,
                                         StepTimes* times = nullptr);

}  // namespace seqc::compiler
