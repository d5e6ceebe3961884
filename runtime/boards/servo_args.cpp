#include "runtime/boards/servo_args.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <string>
#include <utility>

#include "base/units.hpp"
#include "compiler/frontend/profiles.hpp"

namespace seqc::boards {
namespace {

std::string quoted(std::string_view text) { return "'" + std::string(text) + "'"; }

std::string known_names(const compiler::RobotInfo& robot) {
  std::string out;
  for (const auto& s : robot.servos) {
    if (!out.empty()) out += ", ";
    out += s.name + "=" + std::to_string(s.id);
  }
  return out;
}

}  // namespace

Result<std::optional<compiler::RobotInfo>> robot_for_profile(const std::string& profile) {
  if (profile.empty()) return std::optional<compiler::RobotInfo>{};
  const compiler::RobotProfile* p = compiler::find_profile(profile);
  if (p == nullptr) {
    std::string names;
    for (const auto& n : compiler::profile_names()) names += (names.empty() ? "" : ", ") + n;
    return make_error("--robot: unknown profile " + quoted(profile) + " (known: " + names + ")");
  }
  return std::optional<compiler::RobotInfo>{compiler::robot_from_profile(*p)};
}

Result<long long> parse_integer(std::string_view text, const char* field) {
  long long value = 0;
  const char* first = text.data();
  const char* last = text.data() + text.size();
  if (!text.empty() && text[0] == '+') ++first;
  const auto [end, ec] = std::from_chars(first, last, value);
  if (text.empty() || ec == std::errc::invalid_argument || end != last) {
    return make_error(std::string(field) + ": " + quoted(text) + " is not a whole number");
  }
  if (ec == std::errc::result_out_of_range) {
    return make_error(std::string(field) + ": " + quoted(text) + " is far out of range");
  }
  return value;
}

Result<std::uint8_t> parse_servo(std::string_view text,
                                 const std::optional<compiler::RobotInfo>& robot) {
  const bool numeric =
      !text.empty() && text.find_first_not_of("0123456789+-") == std::string_view::npos;
  if (!numeric) {
    if (!robot) {
      return make_error("servo " + quoted(text) +
                        " is not an id; servo names need a profile, e.g. --robot xarm");
    }
    if (const compiler::ServoInfo* s = robot->find_name(text)) return s->id;
    return make_error("servo " + quoted(text) + " is not a servo of the " + robot->profile +
                      " profile (" + known_names(*robot) + ")");
  }
  auto number = parse_integer(text, "servo");
  if (!number) return number.error();
  auto id = lsc::checked_u8(*number, "servo");
  if (!id) return id.error();
  if (robot && robot->find_id(*id) == nullptr) {
    return make_error("servo " + std::to_string(*id) + " is not a servo of the " + robot->profile +
                      " profile (ids " + std::to_string(robot->servos.front().id) + ".." +
                      std::to_string(robot->servos.back().id) + ")");
  }
  return *id;
}

Result<std::vector<std::uint8_t>> parse_servo_list(
    const std::vector<std::string>& texts, const std::optional<compiler::RobotInfo>& robot) {
  if (texts.empty()) return make_error("name at least one servo");
  if (texts.size() > 255) {
    return make_error("at most 255 servos fit in one request, got " + std::to_string(texts.size()));
  }
  std::vector<std::uint8_t> ids;
  for (const std::string& t : texts) {
    auto id = parse_servo(t, robot);
    if (!id) return id.error();
    if (std::find(ids.begin(), ids.end(), *id) != ids.end()) {
      return make_error("servo " + std::to_string(*id) + " is named twice");
    }
    ids.push_back(*id);
  }
  return ids;
}

Result<std::vector<std::uint8_t>> servos_to_read(const std::vector<std::string>& texts,
                                                 const std::optional<compiler::RobotInfo>& robot) {
  if (!texts.empty()) return parse_servo_list(texts, robot);
  if (!robot)
    return make_error("name the servos to read, or give --robot to read all of a profile's");
  std::vector<std::uint8_t> ids;
  for (const auto& s : robot->servos) ids.push_back(s.id);
  return ids;
}

Result<ServoSelection> select_servos(const std::string& profile,
                                     const std::vector<std::string>& texts) {
  auto robot = robot_for_profile(profile);
  if (!robot) return robot.error();
  auto ids = parse_servo_list(texts, *robot);
  if (!ids) return ids.error();
  return ServoSelection{std::move(*robot), std::move(*ids)};
}

Result<RequestedTarget> parse_target(std::string_view text,
                                     const std::optional<compiler::RobotInfo>& robot) {
  const auto eq = text.find('=');
  if (eq == std::string_view::npos || eq == 0 || eq + 1 == text.size()) {
    return make_error("move target " + quoted(text) +
                      " must look like SERVO=POSITION, e.g. 1=500 or claw=200");
  }
  auto id = parse_servo(text.substr(0, eq), robot);
  if (!id) return id.error();
  const std::string field = "position of servo " + std::to_string(*id);
  auto number = parse_integer(text.substr(eq + 1), field.c_str());
  if (!number) return number.error();
  return RequestedTarget{*id, *number};
}

Result<std::vector<RequestedTarget>> parse_targets(
    const std::vector<std::string>& texts, const std::optional<compiler::RobotInfo>& robot) {
  if (texts.size() > 255) return make_error("at most 255 servos fit in one move");
  std::vector<RequestedTarget> targets;
  for (const std::string& text : texts) {
    auto t = parse_target(text, robot);
    if (!t) return t.error();
    for (const RequestedTarget& e : targets) {
      if (e.id == t->id) return make_error("servo " + std::to_string(t->id) + " is named twice");
    }
    targets.push_back(*t);
  }
  return targets;
}

PositionRange position_range(std::uint8_t id, const std::optional<compiler::RobotInfo>& robot) {
  if (robot) {
    if (const compiler::ServoInfo* s = robot->find_id(id)) return {s->min, s->max};
  }
  // Every servo controller profile's range together: what some servo on some controller takes.
  std::optional<PositionRange> all;
  for (const std::string& name : compiler::profile_names()) {
    const compiler::RobotProfile* p = compiler::find_profile(name);
    if (p->kind != compiler::RobotKind::ServoController) continue;
    if (!all) all = PositionRange{p->min, p->max};
    all->min = std::min<long long>(all->min, p->min);
    all->max = std::max<long long>(all->max, p->max);
  }
  return all.value_or(PositionRange{});
}

Result<std::vector<lsc::ServoTarget>> checked_targets(
    const std::vector<RequestedTarget>& targets, const std::optional<compiler::RobotInfo>& robot) {
  std::vector<lsc::ServoTarget> out;
  for (const RequestedTarget& t : targets) {
    const PositionRange range = position_range(t.id, robot);
    if (t.position < range.min || t.position > range.max) {
      const std::string where =
          robot ? " on " + robot->profile
                : " on a servo controller (give --robot for a profile's own range)";
      return make_error("position of servo " + std::to_string(t.id) + " must be " +
                        std::to_string(range.min) + ".." + std::to_string(range.max) + where +
                        ", got " + std::to_string(t.position));
    }
    // The range lies within the wire's ushort and below 0xff00 ("do not move").
    out.push_back({t.id, static_cast<std::uint16_t>(t.position)});
  }
  return out;
}

Result<std::uint16_t> parse_milliseconds(std::string_view text, const char* field) {
  auto time = seqc::parse_time(text);
  if (!time) return make_error(std::string(field) + ": " + time.error().message);
  if (time->unit == seqc::TimeUnit::Beats || time->unit == seqc::TimeUnit::Bars) {
    return make_error(std::string(field) + ": beats need a tempo; give ms or s");
  }
  const double ms = time->unit == seqc::TimeUnit::Seconds ? time->amount * 1000 : time->amount;
  if (ms != std::floor(ms)) {
    return make_error(std::string(field) + ": " + quoted(text) + " is not whole milliseconds");
  }
  const std::string range_field = std::string(field) + " (ms)";
  return lsc::checked_u16(ms > 1e12 ? 1000000000000LL : static_cast<long long>(ms),
                          range_field.c_str());
}

Result<std::uint8_t> parse_group(std::string_view text) {
  auto number = parse_integer(text, "group");
  if (!number) return number.error();
  if (*number < 0 || *number >= lsc::kAllGroups) {
    return make_error("group must be 0..254, got " + std::to_string(*number) +
                      " (255 means every group on the wire; say `all` where a command allows it)");
  }
  return static_cast<std::uint8_t>(*number);
}

Result<GroupTarget> parse_group_target(std::string_view text) {
  if (text == "all") return GroupTarget{lsc::kAllGroups, true};
  auto g = parse_group(text);
  if (!g) return g.error();
  return GroupTarget{*g, false};
}

Result<GroupTarget> erase_target(std::string_view group, bool all) {
  if (all && !group.empty()) return make_error("give GROUP or --all, not both");
  if (!all && group.empty()) return make_error("give a GROUP to erase, or --all");
  return all ? Result<GroupTarget>(GroupTarget{lsc::kAllGroups, true}) : parse_group_target(group);
}

Result<std::uint16_t> run_times(long long times, bool times_given, bool forever) {
  if (forever && times_given) return make_error("give --times or --forever, not both");
  if (forever) return std::uint16_t{0};
  if (times < 1 || times > 65535) {
    return make_error("--times must be 1..65535, got " + std::to_string(times) +
                      " (--forever loops until `seqc group stop`)");
  }
  return static_cast<std::uint16_t>(times);
}

Result<std::uint16_t> parse_speed_percent(std::string_view text) {
  long long value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size() || value < 1 || value > 65535) {
    return make_error("percent must be a whole number 1..65535 (100 = as stored), got " +
                      quoted(text));
  }
  return static_cast<std::uint16_t>(value);
}

Result<std::int16_t> parse_offset(std::string_view text) {
  constexpr long long kOffsetMin = -128;
  constexpr long long kOffsetMax = 127;
  auto number = parse_integer(text, "offset");
  if (!number) return number.error();
  auto offset = lsc::checked_i16(*number, "offset");
  if (!offset) return offset.error();
  if (*number < kOffsetMin || *number > kOffsetMax) {
    return make_error("offset must be " + std::to_string(kOffsetMin) + ".." +
                      std::to_string(kOffsetMax) + ", got " + std::to_string(*number) +
                      " (ServoOffsetRead reports offsets as a signed byte)");
  }
  return *offset;
}

Result<io::Duration> parse_timeout(std::string_view text) {
  // A reply is waited for in clock time: the language's beats and bars mean nothing here, so
  // the parse's own message, which offers them, is not passed on (but its hint for a number
  // without a unit is).
  auto time = seqc::parse_time(text);
  if (!time && time.error().message.find("has no unit") != std::string::npos) {
    return make_error("--timeout: " + time.error().message);
  }
  if (!time || time->unit == seqc::TimeUnit::Beats || time->unit == seqc::TimeUnit::Bars) {
    return make_error("--timeout: '" + std::string(text) +
                      "' is not a time in ms or s; write it like '500ms' or '2s'");
  }
  const double ms = time->unit == seqc::TimeUnit::Seconds ? time->amount * 1000 : time->amount;
  if (ms <= 0 || ms > 3600.0 * 1000) {
    return make_error("--timeout must be more than 0 and at most 1 hour, got '" +
                      std::string(text) + "'");
  }
  return std::chrono::duration_cast<io::Duration>(std::chrono::duration<double, std::milli>(ms));
}

}  // namespace seqc::boards
