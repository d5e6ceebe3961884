// The little value syntaxes of the language: times (500ms, 1.5s, 2b, 1/3b), positions (500,
// 90deg, +50, -10deg) and speeds (400/s, 90deg/s). Each parser returns the parsed value or an error
// message meant for a diagnostic at the value's location.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "base/result.hpp"

namespace seqc {

enum class TimeUnit { Milliseconds, Seconds, Beats, Bars };

struct TimeValue {
  double amount = 0;
  TimeUnit unit = TimeUnit::Milliseconds;
  // A fraction written N/D ("1/3b") is exact: `amount` is only its nearest double, and a
  // consumer that counts exactly reads numerator / denominator. 0 for a decimal ("1.5s"), whose
  // `amount` is what was written.
  std::int64_t numerator = 0;
  std::int64_t denominator = 0;
};

// The largest numerator and denominator a fraction of a time may have: a denominator of 1000
// splits a beat finer than any servo moves, and a numerator of 1,000,000 with it still spans
// every sequence.
inline constexpr std::int64_t kMaxTimeNumerator = 1000000;
inline constexpr std::int64_t kMaxTimeDenominator = 1000;

// "500ms", "1.5s", "2b", "2bar", and fractions of them "1/3b", "5/4b", "1/6bar", "1/3s". A bare
// number or fraction is an error whose message suggests the unit; a fraction with its unit in
// the wrong place ("1b/3", "(1/3)b") one that suggests "1/3b".
Result<TimeValue> parse_time(std::string_view text);

// A time on the clock, "500ms" or "1.5s", in milliseconds; nullopt for anything else, beats
// and bars included (they need a tempo). For options and settings that wait or measure in time.
std::optional<double> parse_clock_ms(std::string_view text);

struct PositionValue {
  bool relative = false;  // written with a sign: +50, -10deg
  bool degrees = false;
  double amount = 0;  // signed for relative values
};

// "500", "90deg", "+50", "-10deg", "+2.5deg". Device units must be whole numbers.
Result<PositionValue> parse_position(std::string_view text);

struct SpeedValue {
  bool degrees = false;
  double per_second = 0;
};

// "400/s" (device units per second) or "90deg/s".
Result<SpeedValue> parse_speed(std::string_view text);

// A non-negative decimal number ("12", "1.5"); false if `text` is not one.
bool parse_decimal(std::string_view text, double& out);

// A distance in device units for messages: "1", "0.5", "12.25" (at most two decimals).
std::string format_units(double units);

// A count with thousands separated, as messages write large numbers: "7,985", "-10,000".
std::string format_grouped(long long n);

// "1.5 s", "750 ms", "12.5 s" style for summaries: seconds with up to 3 decimals, no trailing 0.
std::string format_seconds(std::uint64_t ms);

}  // namespace seqc
