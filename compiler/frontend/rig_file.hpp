// The rig file (`--rig rig.yaml`, docs/music.md "Long songs: the board's clock"): facts about
// one robot's hardware that stay true from one song to the next, in a small YAML map:
//
//   clock_ppm: +8000      # the board's clock error, as `seqc calibrate clock` prints it
//   audio_offset: 40ms    # the audio's delay, for the commands that play music
//
// Every key is optional. Unknown keys and bad values are errors with the key's location (clang's
// form, "did you mean" for a misspelt key); all of them are reported in one run. The reading is
// pure: the caller reads the file and renders the diagnostics.
#pragma once

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "base/diagnostics.hpp"
#include "base/source.hpp"
#include "base/result.hpp"

namespace seqc::compiler {

struct Rig {
  std::optional<std::int32_t> clock_ppm;
  std::optional<std::chrono::nanoseconds> audio_offset;  // may be negative
};

// The largest clock error a rig file or --clock-ppm takes, either way (20 %).
inline constexpr std::int32_t kMaxRigClockPpm = 200000;

// "+8000", "-10000", "0": a whole number of ppm within kMaxRigClockPpm.
Result<std::int32_t> parse_clock_ppm(std::string_view text);

// Reads file `file` of `sources` as a rig file; nullopt when it has errors (in `diags`).
std::optional<Rig> parse_rig(const seqc::SourceManager& sources, std::uint32_t file,
                             seqc::Diagnostics& diags);

}  // namespace seqc::compiler
