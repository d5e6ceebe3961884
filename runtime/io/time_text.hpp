// Durations and clock readings as the runtime writes them in reports, notes and records. One
// spelling per form, so an upload's note, a play's report and an emulator's record agree:
// "0.536 s", "12.50 ms", "3.000125" (seconds since the clock's zero, microseconds truncated),
// "250 ms" / "1.5 s".
#pragma once

#include <chrono>
#include <cstdio>
#include <string>

#include "base/units.hpp"
#include "runtime/io/clock.hpp"

namespace seqc::io {

// "0.536 s" with `decimals` places.
inline std::string seconds_text(Duration d, int decimals = 3) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.*f s", decimals, std::chrono::duration<double>(d).count());
  return buf;
}

// A link's pace as a report names it: "at 9600 baud" for a byte stream (10 bits a byte), "at one
// report per 1.0 ms" for one that sends whole reports on an interval.
inline std::string pace_text(double seconds_per_byte, Duration frame_interval);

// "12.5 ms" with `decimals` places.
inline std::string ms_text(Duration d, int decimals) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.*f ms", decimals,
                std::chrono::duration<double, std::milli>(d).count());
  return buf;
}

// "S.uuuuuu": whole seconds since the clock's zero and the microseconds, truncated, so a record
// never shows a time later than the one it was taken at.
inline std::string stamp_text(TimePoint t) {
  const auto us = std::chrono::duration_cast<std::chrono::microseconds>(t).count();
  std::string text = std::to_string(us / 1000000);
  const std::string fraction = std::to_string(us % 1000000);
  text += '.';
  text.append(6 - fraction.size(), '0');
  text += fraction;
  return text;
}

// "250 ms" below a second, else seqc::format_seconds ("1.5 s").
inline std::string duration_text(Duration d) {
  const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(d).count();
  if (ms < 1000) return std::to_string(ms) + " ms";
  return seqc::format_seconds(static_cast<std::uint64_t>(ms));
}

inline std::string pace_text(double seconds_per_byte, Duration frame_interval) {
  if (seconds_per_byte > 0) {
    return "at " + std::to_string(static_cast<long>(10.0 / seconds_per_byte + 0.5)) + " baud";
  }
  return "at one report per " + ms_text(frame_interval, 1);
}

}  // namespace seqc::io
