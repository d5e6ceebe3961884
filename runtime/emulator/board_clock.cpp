#include "runtime/emulator/board_clock.hpp"

namespace seqc::emu {

Result<std::int32_t> parse_clock_error(std::string_view text) {
  const std::string quoted = "clock '" + std::string(text) + "'";
  const auto bad = [&] {
    return make_error(quoted + " is not a clock error (e.g. +0.8%, -1%, +120ppm)");
  };
  std::string_view s = text;
  bool negative = false;
  if (!s.empty() && (s.front() == '+' || s.front() == '-')) {
    negative = s.front() == '-';
    s.remove_prefix(1);
  }
  std::size_t decimals = 0;  // how many the unit allows
  if (s.ends_with("ppm")) {
    s.remove_suffix(3);
  } else if (s.ends_with('%')) {
    s.remove_suffix(1);
    decimals = 4;
  } else if (s != "0") {
    return bad();
  }
  const std::size_t dot = s.find('.');
  const std::string_view whole = s.substr(0, dot);
  const std::string_view fraction = dot == std::string_view::npos ? "" : s.substr(dot + 1);
  if (whole.empty() || whole.size() > 7 || (dot != std::string_view::npos && fraction.empty())) {
    return bad();
  }
  if (fraction.size() > decimals) {
    return make_error(quoted + ": a clock error is a whole number of ppm (" +
                      (decimals == 0 ? "no decimals" : "at most 4 decimals of a percent") + ")");
  }
  std::int64_t value = 0;
  for (const std::string_view part : {whole, fraction}) {
    for (const char c : part) {
      if (c < '0' || c > '9') return bad();
      value = value * 10 + (c - '0');
    }
  }
  // Padded to four decimals a percent's digits count ppm (0.0001 % = 1 ppm).
  for (std::size_t i = fraction.size(); i < decimals; ++i) value *= 10;
  if (value > kMaxClockPpm) {
    return make_error(quoted + " is beyond +-20% (" + std::to_string(kMaxClockPpm) + " ppm)");
  }
  return static_cast<std::int32_t>(negative ? -value : value);
}

std::string format_clock_error(std::int32_t ppm) {
  return (ppm > 0 ? "+" : "") + std::to_string(ppm) + "ppm";
}

io::Duration board_to_host(io::Duration board, std::int32_t ppm) {
  if (ppm == 0) return board;
  // In two parts so that board x 1e6 cannot overflow: q whole periods and the rest.
  const std::int64_t period = 1000000 + ppm;
  const std::int64_t ns = board.count();
  const std::int64_t q = ns / period;
  const std::int64_t r = ns % period;
  return io::Duration{q * 1000000 + r * 1000000 / period};
}

}  // namespace seqc::emu
