// `seqc follow FILE --ltc SOURCE --start HH:MM:SS:FF`, the timecode half in words: the show
// clock (runtime/follow/ltc_clock.hpp) made from what the user typed. SOURCE is a WAV file when
// it names one that exists (played at real-time pace on the context's clock: a rehearsal from a
// recording), else a PulseAudio source ("default", a line input, "NAME.monitor"), recorded at
// 48 kHz on the context's clock, which must then be the host's monotonic one (main's).
//
// The errors name the option: "--start: expected a timecode HH:MM:SS:FF (HH:MM:SS;FF for
// drop-frame), got \"12:00\"", "--ltc: cannot record from PulseAudio source \"x\": No such
// entity", "--ltc: show.wav: no such file". The command prints them as `seqc: error: ...` and
// exits with the usage (START) or I/O (SOURCE) code.
#pragma once

#include <memory>
#include <string>

#include "base/result.hpp"
#include "protocol/ltc_timecode.hpp"
#include "runtime/cli/context.hpp"
#include "runtime/follow/show_clock.hpp"

namespace seqc::cli {

// --start, read.
Result<ltc::Timecode> parse_ltc_start(const std::string& text);

// The LTC show clock on SOURCE from START (already read by parse_ltc_start).
Result<std::unique_ptr<follow::ShowClock>> open_ltc_clock(const std::string& source,
                                                          const ltc::Timecode& start, Context& ctx);

}  // namespace seqc::cli
