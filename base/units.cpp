#include "base/units.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <string>

namespace seqc {
namespace {

std::string not_a_speed(std::string_view text) {
  return fmt::format(
      "'{}' is not a speed; write device units per second ('400/s') or degrees per second "
      "('90deg/s')",
      text);
}

bool is_digit(char c) { return c >= '0' && c <= '9'; }

// Splits "1.5ms" into the longest decimal prefix and the rest.
std::size_t number_length(std::string_view text) {
  std::size_t i = 0;
  while (i < text.size() && is_digit(text[i])) ++i;
  if (i < text.size() && text[i] == '.') {
    std::size_t j = i + 1;
    while (j < text.size() && is_digit(text[j])) ++j;
    if (j > i + 1) i = j;
  }
  return i;
}

}  // namespace

bool parse_decimal(std::string_view text, double& out) {
  if (text.empty() || number_length(text) != text.size() || !is_digit(text[0])) return false;
  // Decimal digits only, so this cannot fail; a hand-rolled parse avoids locale surprises.
  double value = 0;
  std::size_t i = 0;
  for (; i < text.size() && text[i] != '.'; ++i) value = value * 10 + (text[i] - '0');
  double scale = 0.1;
  for (++i; i < text.size(); ++i, scale /= 10) value += (text[i] - '0') * scale;
  out = value;
  return true;
}

std::optional<double> parse_clock_ms(std::string_view text) {
  auto time = parse_time(text);
  if (!time || time->unit == TimeUnit::Beats || time->unit == TimeUnit::Bars) return std::nullopt;
  return time->unit == TimeUnit::Seconds ? time->amount * 1000 : time->amount;
}

namespace {

// The unit of a time, or nullopt for text that names none.
std::optional<TimeUnit> time_unit(std::string_view unit) {
  if (unit == "ms") return TimeUnit::Milliseconds;
  if (unit == "s") return TimeUnit::Seconds;
  if (unit == "b") return TimeUnit::Beats;
  if (unit == "bar" || unit == "bars") return TimeUnit::Bars;
  return std::nullopt;
}

// "1b/3" and "(1/3)b" as the fraction they mean to be, "1/3b"; empty when the text is no such
// misplaced fraction.
std::string misplaced_fraction(std::string_view text) {
  std::string bare;
  for (char c : text) {
    if (c != '(' && c != ')') bare += c;
  }
  const std::size_t slash = bare.find('/');
  if (slash == std::string::npos) return "";
  const std::string_view before = std::string_view(bare).substr(0, slash);
  const std::string_view after = std::string_view(bare).substr(slash + 1);
  const std::size_t n = number_length(before);
  std::string candidate;
  if (n > 0 && n < before.size() && time_unit(before.substr(n)) && !after.empty() &&
      number_length(after) == after.size()) {
    candidate = std::string(before.substr(0, n)) + "/" + std::string(after) +
                std::string(before.substr(n));  // "1b/3"
  } else if (bare != text) {
    candidate = bare;  // "(1/3)b"
  }
  if (candidate.empty() || candidate == text) return "";
  return candidate;
}

std::string not_a_time(std::string_view text) {
  const std::string fraction = misplaced_fraction(text);
  if (!fraction.empty()) {
    return fmt::format(
        "'{}' is not a time; a fraction is written whole over whole with the unit after it, "
        "e.g. '{}'",
        text, fraction);
  }
  return fmt::format("'{}' is not a time; write it like '500ms', '1.5s' or '2b' (beats)", text);
}

// The whole number `digits` when it is one no larger than `max`.
std::optional<std::int64_t> whole_up_to(std::string_view digits, std::int64_t max) {
  if (digits.empty() || number_length(digits) != digits.size()) return std::nullopt;
  std::int64_t value = 0;
  for (char c : digits) {
    if (!is_digit(c)) return std::nullopt;
    value = value * 10 + (c - '0');
    if (value > max) return std::nullopt;
  }
  return value;
}

// "1/3b": numerator, slash, denominator, unit.
Result<TimeValue> parse_fraction_time(std::string_view text, std::size_t slash) {
  const std::string_view top = text.substr(0, slash);
  const std::string_view rest = text.substr(slash + 1);
  const std::size_t n = number_length(rest);
  const std::string_view bottom = rest.substr(0, n);
  const std::string_view unit_text = rest.substr(n);
  if (top.empty() || number_length(top) != top.size() || n == 0) {
    return make_error(not_a_time(text));
  }
  const std::optional<std::int64_t> num = whole_up_to(top, kMaxTimeNumerator);
  const std::optional<std::int64_t> den = whole_up_to(bottom, kMaxTimeDenominator);
  if (!num) {
    return make_error(fmt::format(
        "'{}': the numerator of a fraction must be a whole number up to {}; write longer times in "
        "a larger unit",
        text, format_grouped(kMaxTimeNumerator)));
  }
  if (!den || *den == 0) {
    return make_error(fmt::format(
        "'{}': the denominator of a fraction must be a whole number from 1 to {}, e.g. '1/3b'",
        text, format_grouped(kMaxTimeDenominator)));
  }
  if (unit_text.empty()) {
    return make_error(
        fmt::format("time '{}' has no unit; write '{}b' (beats), '{}bar', '{}s' or '{}ms'", text,
                    text, text, text, text));
  }
  const std::optional<TimeUnit> unit = time_unit(unit_text);
  if (!unit) {
    return make_error("unknown time unit '" + std::string(unit_text) + "' in '" +
                      std::string(text) + "'; use ms, s, b (beats) or bar");
  }
  TimeValue v;
  v.unit = *unit;
  v.amount = static_cast<double>(*num) / static_cast<double>(*den);
  v.numerator = *num;
  v.denominator = *den;
  return v;
}

}  // namespace

Result<TimeValue> parse_time(std::string_view text) {
  const std::size_t n = number_length(text);
  if (n > 0 && n < text.size() && text[n] == '/') return parse_fraction_time(text, n);
  double amount = 0;
  if (n == 0 || !parse_decimal(text.substr(0, n), amount)) return make_error(not_a_time(text));
  const std::string_view unit = text.substr(n);
  if (unit.empty()) {
    return make_error("time '" + std::string(text) + "' has no unit; write '" + std::string(text) +
                      "ms' or '" + std::string(text) + "s'");
  }
  if (const std::optional<TimeUnit> u = time_unit(unit)) return TimeValue{amount, *u, 0, 0};
  const std::string fraction = misplaced_fraction(text);
  if (!fraction.empty()) return make_error(not_a_time(text));
  return make_error("unknown time unit '" + std::string(unit) + "' in '" + std::string(text) +
                    "'; use ms, s, b (beats) or bar");
}

Result<PositionValue> parse_position(std::string_view text) {
  PositionValue v;
  std::string_view rest = text;
  double sign = 1;
  if (!rest.empty() && (rest[0] == '+' || rest[0] == '-')) {
    v.relative = true;
    sign = rest[0] == '-' ? -1 : 1;
    rest.remove_prefix(1);
  }
  if (rest.size() >= 3 && rest.substr(rest.size() - 3) == "deg") {
    v.degrees = true;
    rest.remove_suffix(3);
  }
  double amount = 0;
  if (!parse_decimal(rest, amount)) {
    return make_error(fmt::format(
        "'{}' is not a position; write device units (500), degrees (90deg) or a relative move "
        "(+50, -10deg)",
        text));
  }
  // 1000.0 is a whole number; 500.5 is not, and "500.5deg" would be another value entirely
  // (an angle), so the hint offers the whole numbers around it.
  if (!v.degrees && amount != std::floor(amount)) {
    const std::string sign_text = v.relative ? std::string(1, text[0]) : "";
    return make_error(fmt::format(
        "position '{}' is not a whole number of device units; round it to {}{} or {}{} (an angle "
        "may have a fraction: 90.5deg)",
        text, sign_text, std::floor(amount), sign_text, std::ceil(amount)));
  }
  v.amount = sign * amount;
  return v;
}

Result<SpeedValue> parse_speed(std::string_view text) {
  SpeedValue v;
  std::string_view rest = text;
  if (rest.size() < 2 || rest.substr(rest.size() - 2) != "/s") {
    return make_error(not_a_speed(text));
  }
  rest.remove_suffix(2);
  if (rest.size() >= 3 && rest.substr(rest.size() - 3) == "deg") {
    v.degrees = true;
    rest.remove_suffix(3);
  }
  if (!parse_decimal(rest, v.per_second) || v.per_second <= 0) {
    return make_error(not_a_speed(text));
  }
  return v;
}

std::string format_grouped(long long n) {
  const std::string digits = std::to_string(n < 0 ? -n : n);
  std::string out = n < 0 ? "-" : "";
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return out;
}

std::string format_seconds(std::uint64_t ms) {
  std::string s = std::to_string(ms / 1000);
  std::uint64_t frac = ms % 1000;
  if (frac != 0) {
    std::string f = std::to_string(frac);
    f.insert(0, 3 - f.size(), '0');
    while (f.back() == '0') f.pop_back();
    s += "." + f;
  }
  return s + " s";
}

std::string format_units(double units) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", units);
  std::string out = buf;
  while (!out.empty() && out.back() == '0') out.pop_back();
  if (!out.empty() && out.back() == '.') out.pop_back();
  return out == "-0" ? "0" : out;
}

}  // namespace seqc
