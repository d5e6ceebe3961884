// SMPTE timecode (hours:minutes:seconds:frames) and its arithmetic at the four rates LTC carries
// here: 24, 25 and 30 frames a second, and 29.97 drop-frame. Pure: no I/O, nothing thrown.
//
// A frame count is the number of frames since 00:00:00:00. At 29.97 drop-frame the count is of
// real frames (30000/1001 a second): frame numbers 0 and 1 are skipped at the start of every
// minute except minutes 0, 10, 20, ..., so the label runs 00:00:59;29 -> 00:01:00;02, and
// 00:10:00;00 is frame 17982. docs/protocol/ltc.md has the layout and the rule.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "base/result.hpp"

namespace seqc::ltc {

enum class FrameRate { Fps24, Fps25, Fps2997Drop, Fps30 };

struct Timecode {
  int hours = 0;
  int minutes = 0;
  int seconds = 0;
  int frames = 0;
  bool drop_frame = false;  // written with ';' or '.' before the frames
  friend bool operator==(const Timecode&, const Timecode&) = default;
};

// Frames a second as counted in the label: 24, 25, 30 (30 also for 29.97 drop-frame).
int nominal_fps(FrameRate rate);
// Real frames a second: 24, 25, 30000/1001, 30.
double real_fps(FrameRate rate);
// "25 fps", "29.97 fps drop-frame".
std::string rate_name(FrameRate rate);

// Whether `tc` names a frame at `rate`: fields in range (frames below nominal_fps, hours below
// 24), and at drop-frame not one of the skipped labels (frames 0 and 1 of a minute not a
// multiple of ten).
bool exists_at(const Timecode& tc, FrameRate rate);

// The count of the frame `tc` labels (exists_at must hold), and back. to_timecode wraps at 24
// hours and sets drop_frame for Fps2997Drop.
std::int64_t frame_count(const Timecode& tc, FrameRate rate);
Timecode to_timecode(std::int64_t count, FrameRate rate);

// When frame `count` starts, in milliseconds from 00:00:00:00 in real time (count / real_fps).
double frame_start_ms(std::int64_t count, FrameRate rate);

// "HH:MM:SS:FF", or "HH:MM:SS;FF" for drop-frame.
std::string to_text(const Timecode& tc);

// Reads "HH:MM:SS:FF" (each field one or two digits); ';' or '.' before FF (or as every
// separator) marks drop-frame. Checks hours < 24, minutes and seconds < 60, frames < 30, and
// that a drop-frame label is not one that drop-frame skips. The Error is the reason alone
// ("expected HH:MM:SS:FF ..."): the caller names the option or the file.
Result<Timecode> parse_timecode(std::string_view text);

}  // namespace seqc::ltc
