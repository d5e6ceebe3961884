#include "runtime/emulator/xarm_config.hpp"

#include <algorithm>

#include <array>
#include <charconv>
#include <cmath>
#include <sstream>
#include <vector>

#include "base/diagnostics.hpp"
#include "runtime/emulator/board_clock.hpp"

namespace seqc::emu {
namespace {

// In the order the "known:" list of an unknown key has always named them.
constexpr FaultKey kKeys[] = {
    {"seed", FaultValue::Seed, "seed of the faults (1)"},
    {"drop", FaultValue::Rate, "an incoming frame is lost"},
    {"corrupt", FaultValue::Rate, "a byte of a request or a reply is flipped"},
    {"late", FaultValue::Rate, "a reply comes late-by later"},
    {"late-by", FaultValue::Duration, "how much later a late reply comes (400ms)"},
    {"dup", FaultValue::Rate, "a reply is sent twice"},
    {"silent-after", FaultValue::Count, "no answer after N frames"},
    {"hangup-at", FaultValue::Count, "the link closes when frame N arrives"},
    {"back-after", FaultValue::Duration, "a hung-up device returns, on a new terminal"},
    {"reset", FaultValue::Rate,
     "a power dip: the controller forgets a download and is deaf for boot-time"},
    {"reset-at", FaultValue::Count, "a power dip when frame N arrives"},
    {"boot-time", FaultValue::Duration, "how long a reset keeps it deaf (300ms)"},
    {"busy", FaultValue::Rate,
     "a frame keeps the controller busy-for longer (frames meanwhile are dropped)"},
    {"busy-for", FaultValue::Duration, "how long a busy frame keeps it (400ms)"},
    {"frame-gap", FaultValue::Duration,
     "a partial request is dropped when the next byte comes later than this (not the "
     "firmware's behaviour)"},
    {"split", FaultValue::Rate,
     "a reply reaches the host in two pieces (a USB-serial adapter's latency timer)"},
    {"clock", FaultValue::ClockError,
     "the controller's clock is this fast or slow (+0.8%, -1%, +120ppm): stored groups play "
     "that much quicker or slower"},
};

std::string unknown_key_message(std::string_view key) {
  std::string msg = "unknown fault '" + std::string(key) + "'";
  const std::string best = seqc::did_you_mean(key, [] {
    std::vector<std::string> keys;
    for (const FaultKey& k : kKeys) keys.emplace_back(k.key);
    return keys;
  }());
  if (!best.empty()) msg += "; did you mean '" + best + "'?";
  msg += " (known:";
  for (std::size_t i = 0; i < std::size(kKeys); ++i) {
    msg += std::string(i == 0 ? " " : ", ") + std::string(kKeys[i].key);
  }
  msg += ")";
  return msg;
}

Result<std::uint64_t> parse_unsigned(std::string_view key, std::string_view text) {
  std::uint64_t v = 0;
  auto [p, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc{} || p != text.data() + text.size() || text.empty()) {
    return make_error("fault '" + std::string(key) + "': '" + std::string(text) +
                      "' is not a non-negative integer");
  }
  return v;
}

Result<double> parse_rate(std::string_view key, std::string_view text) {
  // std::from_chars for double is available in libstdc++ 11+.
  double v = 0;
  auto [p, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc{} || p != text.data() + text.size() || text.empty()) {
    return make_error("fault '" + std::string(key) + "': '" + std::string(text) +
                      "' is not a number");
  }
  if (!(v >= 0.0 && v <= 1.0)) {
    return make_error("fault '" + std::string(key) + "': rate " + std::string(text) +
                      " is outside 0..1");
  }
  return v;
}

Result<io::Duration> parse_duration(std::string_view key, std::string_view text) {
  struct Unit {
    std::string_view suffix;
    std::int64_t ns;
  };
  constexpr std::array<Unit, 4> kUnits = {Unit{"ns", 1}, Unit{"us", 1000}, Unit{"ms", 1000000},
                                          Unit{"s", 1000000000}};
  std::int64_t scale = 1000000;  // bare number: milliseconds
  std::string_view digits = text;
  for (const auto& u : kUnits) {
    if (text.size() > u.suffix.size() && text.ends_with(u.suffix)) {
      scale = u.ns;
      digits = text.substr(0, text.size() - u.suffix.size());
      break;
    }
  }
  std::uint64_t v = 0;
  auto [p, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), v);
  if (ec != std::errc{} || p != digits.data() + digits.size() || digits.empty() ||
      v > static_cast<std::uint64_t>(INT64_MAX / scale)) {
    return make_error("fault '" + std::string(key) + "': '" + std::string(text) +
                      "' is not a duration (e.g. 400ms, 2s)");
  }
  return io::Duration{static_cast<std::int64_t>(v) * scale};
}

std::string format_duration(io::Duration d) {
  auto ns = d.count();
  if (ns % 1000000000 == 0) return std::to_string(ns / 1000000000) + "s";
  if (ns % 1000000 == 0) return std::to_string(ns / 1000000) + "ms";
  if (ns % 1000 == 0) return std::to_string(ns / 1000) + "us";
  return std::to_string(ns) + "ns";
}

std::string format_rate(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

}  // namespace

std::span<const FaultKey> fault_keys() { return kKeys; }

bool XArmFaults::any() const {
  return drop > 0 || corrupt > 0 || late_ack > 0 || duplicate_ack > 0 || silent_after ||
         hangup_at || reset > 0 || reset_at || busy > 0 || frame_gap.count() > 0 || split > 0;
}

Result<XArmFaults> parse_faults(std::string_view spec) {
  XArmFaults f;
  std::size_t pos = 0;
  while (pos <= spec.size()) {
    std::size_t comma = spec.find(',', pos);
    if (comma == std::string_view::npos) comma = spec.size();
    std::string_view item = spec.substr(pos, comma - pos);
    pos = comma + 1;
    if (item.empty()) {
      if (comma == spec.size()) break;
      continue;
    }
    std::size_t eq = item.find('=');
    if (eq == std::string_view::npos) {
      return make_error("fault '" + std::string(item) + "' needs a value (key=value)");
    }
    std::string_view key = item.substr(0, eq);
    std::string_view value = item.substr(eq + 1);
    // The table decides which keys exist (fault_keys); the branches below give each its value.
    if (std::none_of(std::begin(kKeys), std::end(kKeys),
                     [&](const FaultKey& k) { return k.key == key; })) {
      return make_error(unknown_key_message(key));
    }
    if (key == "seed") {
      auto v = parse_unsigned(key, value);
      if (!v) return v.error();
      f.seed = *v;
    } else if (key == "drop" || key == "corrupt" || key == "late" || key == "dup" ||
               key == "reset" || key == "busy" || key == "split") {
      auto v = parse_rate(key, value);
      if (!v) return v.error();
      (key == "drop"      ? f.drop
       : key == "corrupt" ? f.corrupt
       : key == "late"    ? f.late_ack
       : key == "reset"   ? f.reset
       : key == "busy"    ? f.busy
       : key == "split"   ? f.split
                          : f.duplicate_ack) = *v;
    } else if (key == "late-by" || key == "boot-time" || key == "busy-for" || key == "frame-gap") {
      auto v = parse_duration(key, value);
      if (!v) return v.error();
      (key == "late-by"     ? f.late_by
       : key == "boot-time" ? f.boot_time
       : key == "busy-for"  ? f.busy_for
                            : f.frame_gap) = *v;
    } else if (key == "back-after") {
      auto v = parse_duration(key, value);
      if (!v) return v.error();
      f.back_after = *v;
    } else if (key == "clock") {
      auto v = parse_clock_error(value);
      if (!v) return v.error();
      f.clock_ppm = *v;
    } else if (key == "reset-at") {
      auto v = parse_unsigned(key, value);
      if (!v) return v.error();
      if (*v == 0) return make_error("fault 'reset-at': frames count from 1");
      f.reset_at = static_cast<std::size_t>(*v);
    } else if (key == "silent-after") {
      auto v = parse_unsigned(key, value);
      if (!v) return v.error();
      f.silent_after = static_cast<std::size_t>(*v);
    } else if (key == "hangup-at") {
      auto v = parse_unsigned(key, value);
      if (!v) return v.error();
      if (*v == 0) return make_error("fault 'hangup-at': frames count from 1");
      f.hangup_at = static_cast<std::size_t>(*v);
    } else {
      return make_error(unknown_key_message(key));
    }
    if (comma == spec.size()) break;
  }
  return f;
}

Result<ServoPositions> parse_positions(std::string_view spec) {
  ServoPositions out;
  std::size_t pos = 0;
  while (pos < spec.size()) {
    std::size_t comma = spec.find(',', pos);
    if (comma == std::string_view::npos) comma = spec.size();
    const std::string_view item = spec.substr(pos, comma - pos);
    pos = comma + 1;
    const std::size_t eq = item.find('=');
    if (eq == std::string_view::npos) {
      return make_error("position '" + std::string(item) + "' must be ID=POSITION, e.g. 1=300");
    }
    auto id = parse_unsigned("servo id", item.substr(0, eq));
    auto p = parse_unsigned("position", item.substr(eq + 1));
    if (!id || *id < 1 || *id > 253) {
      return make_error("position '" + std::string(item) + "': servo ids are 1-253");
    }
    if (!p || *p > 1000) {
      return make_error("position '" + std::string(item) + "': positions are 0-1000");
    }
    out.emplace_back(static_cast<std::uint8_t>(*id), static_cast<std::uint16_t>(*p));
  }
  return out;
}

Status apply_emulator_options(std::string_view spec, XArmConfig& config) {
  std::string faults;
  std::string positions;
  std::size_t pos = 0;
  while (pos < spec.size()) {
    std::size_t comma = spec.find(',', pos);
    if (comma == std::string_view::npos) comma = spec.size();
    const std::string item(spec.substr(pos, comma - pos));
    pos = comma + 1;
    if (item.starts_with("baud=")) {
      auto baud = parse_unsigned("baud", std::string_view(item).substr(5));
      if (!baud || *baud > 4000000)
        return make_error("'" + item + "': baud is 0 (unpaced) to 4000000");
      config.baud = static_cast<std::uint32_t>(*baud);
      continue;
    }
    if (item.starts_with("groups=") || item.starts_with("flash=")) {
      const bool groups = item[0] == 'g';
      const std::string_view key = groups ? "groups" : "flash";
      const std::uint64_t most = groups ? kGroupCount : kGroupCount * lsc::kMaxActions;
      auto n = parse_unsigned(key, std::string_view(item).substr(key.size() + 1));
      if (!n || *n < 1 || *n > most) {
        return make_error("'" + item + "': " + std::string(key) + " is 1 to " +
                          std::to_string(most));
      }
      (groups ? config.store.groups : config.store.flash_actions) = *n;
      continue;
    }
    std::string& into = !item.empty() && item[0] >= '0' && item[0] <= '9' ? positions : faults;
    into += (into.empty() ? "" : ",") + item;
  }
  auto f = parse_faults(faults);
  if (!f) return f.error();
  auto p = parse_positions(positions);
  if (!p) return p.error();
  config.faults = *f;
  config.initial_positions = *p;
  for (const auto& [id, position] : *p) {
    config.servo_count = std::max<std::size_t>(config.servo_count, id);
  }
  return Ok{};
}

std::string describe_faults(const XArmFaults& f) {
  std::string out;
  auto add = [&](const std::string& item) {
    if (!out.empty()) out += ",";
    out += item;
  };
  const XArmFaults defaults;
  if (f.drop > 0) add("drop=" + format_rate(f.drop));
  if (f.corrupt > 0) add("corrupt=" + format_rate(f.corrupt));
  if (f.late_ack > 0) add("late=" + format_rate(f.late_ack));
  if (f.late_by != defaults.late_by) add("late-by=" + format_duration(f.late_by));
  if (f.duplicate_ack > 0) add("dup=" + format_rate(f.duplicate_ack));
  if (f.silent_after) add("silent-after=" + std::to_string(*f.silent_after));
  if (f.hangup_at) add("hangup-at=" + std::to_string(*f.hangup_at));
  if (f.back_after) add("back-after=" + format_duration(*f.back_after));
  if (f.reset > 0) add("reset=" + format_rate(f.reset));
  if (f.reset_at) add("reset-at=" + std::to_string(*f.reset_at));
  if ((f.reset > 0 || f.reset_at) && f.boot_time != defaults.boot_time) {
    add("boot-time=" + format_duration(f.boot_time));
  }
  if (f.busy > 0) add("busy=" + format_rate(f.busy));
  if (f.busy > 0 && f.busy_for != defaults.busy_for) {
    add("busy-for=" + format_duration(f.busy_for));
  }
  if (f.frame_gap.count() > 0) add("frame-gap=" + format_duration(f.frame_gap));
  if (f.split > 0) add("split=" + format_rate(f.split));
  if (f.clock_ppm != 0) add("clock=" + format_clock_error(f.clock_ppm));
  if (out.empty()) return "none";
  if (f.seed != defaults.seed) add("seed=" + std::to_string(f.seed));
  return out;
}

}  // namespace seqc::emu
