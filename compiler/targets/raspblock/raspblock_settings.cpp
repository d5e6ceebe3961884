#include "compiler/targets/raspblock/raspblock_settings.hpp"

#include <array>
#include <string>
#include <string_view>

#include "compiler/frontend/robot_section.hpp"

namespace seqc::compiler {
namespace {

struct Axis {
  std::string_view name;
  int limit;
};
// The rocker's ranges: X and Y -25..25 (document); Z -200..200 (docs/protocol/raspblock.md reading,
// kept in protocol/raspblock/raspblock.cpp).
constexpr std::array<Axis, 3> kAxes = {{{"x", 25}, {"y", 25}, {"z", 200}}};

constexpr std::array<std::string_view, 8> kGainNames = {"speed_kp",    "speed_ki",    "position_kp",
                                                        "position_ki", "position_kd", "yaw_kp",
                                                        "yaw_ki",      "yaw_kd"};

// A whole number within [-limit, limit], written with an optional sign.
std::optional<int> parse_signed(const YamlNode& node, int limit, const std::string& what,
                                Reporter& reporter) {
  const std::string range = std::to_string(-limit) + " to " + std::to_string(limit);
  if (!node.is_scalar()) {
    reporter.error(node.location, what + " must be a whole number " + range);
    return std::nullopt;
  }
  std::string_view s = node.scalar;
  int sign = 1;
  if (!s.empty() && (s[0] == '-' || s[0] == '+')) {
    sign = s[0] == '-' ? -1 : 1;
    s.remove_prefix(1);
  }
  long long v = 0;
  bool ok = !s.empty() && s.size() <= 9;
  for (char c : s) {
    ok = ok && c >= '0' && c <= '9';
    if (ok) v = v * 10 + (c - '0');
  }
  if (!ok) {
    reporter.error(node.location,
                   "'" + node.scalar + "' is not a whole number; " + what + " is " + range);
    return std::nullopt;
  }
  v *= sign;
  if (v < -limit || v > limit) {
    reporter.error(node.location, what + " must be " + range + ", not " + node.scalar);
    return std::nullopt;
  }
  return static_cast<int>(v);
}

}  // namespace

std::optional<raspblock::PidAdjust> parse_pid_section(const YamlNode& pid, Reporter& reporter) {
  if (!pid.is_map()) {
    reporter.error(pid.location,
                   "'pid' must be a map: mode (speed or position) and the "
                   "gains speed_kp ... yaw_kd, each 0-255");
    return std::nullopt;
  }
  reporter.check_keys(pid,
                      {"mode", "speed_kp", "speed_ki", "position_kp", "position_ki", "position_kd",
                       "yaw_kp", "yaw_ki", "yaw_kd"},
                      "in 'pid'");
  raspblock::PidAdjust p;
  bool ok = true;
  std::string missing;
  if (const YamlNode* m = pid.find("mode")) {
    if (m->is_scalar() && m->scalar == "speed") {
      p.mode = raspblock::PidMode::Speed;
    } else if (m->is_scalar() && m->scalar == "position") {
      p.mode = raspblock::PidMode::Position;
    } else {
      reporter.unknown(m->location, "pid mode", m->is_scalar() ? m->scalar : "",
                       {"speed", "position"});
      ok = false;
    }
  } else {
    missing = "mode";
  }
  std::uint8_t* gains[] = {&p.speed_kp,    &p.speed_ki, &p.position_kp, &p.position_ki,
                           &p.position_kd, &p.yaw_kp,   &p.yaw_ki,      &p.yaw_kd};
  for (std::size_t i = 0; i < kGainNames.size(); ++i) {
    const YamlNode* g = pid.find(kGainNames[i]);
    if (g == nullptr) {
      missing += std::string(missing.empty() ? "" : ", ") + std::string(kGainNames[i]);
      continue;
    }
    auto v = parse_integer(*g, 0, 255, "'" + std::string(kGainNames[i]) + "'", reporter);
    if (v) {
      *gains[i] = static_cast<std::uint8_t>(*v);
    } else {
      ok = false;
    }
  }
  if (!missing.empty()) {
    reporter.error(pid.location,
                   "'pid' sets every value at once, so it needs all of mode, "
                   "speed_kp, speed_ki, position_kp, position_ki, "
                   "position_kd, yaw_kp, yaw_ki, yaw_kd; missing: " +
                       missing);
    return std::nullopt;
  }
  if (!ok) return std::nullopt;
  return p;
}

std::optional<raspblock::Rocker> parse_drive(const YamlNode& drive, Reporter& reporter) {
  if (!drive.is_map()) {
    reporter.error(drive.location,
                   "'drive' takes a map of speeds, e.g. {x: 10, y: 0, z: 0} "
                   "(x, y -25 to 25; z -200 to 200)");
    return std::nullopt;
  }
  reporter.check_keys(drive, {"x", "y", "z"}, "in 'drive'");
  int values[3] = {0, 0, 0};
  bool ok = true;
  for (std::size_t i = 0; i < kAxes.size(); ++i) {
    if (const YamlNode* n = drive.find(kAxes[i].name)) {
      auto v = parse_signed(*n, kAxes[i].limit, "'" + std::string(kAxes[i].name) + "'", reporter);
      if (v) {
        values[i] = *v;
      } else {
        ok = false;
      }
    }
  }
  if (!ok) return std::nullopt;
  return raspblock::Rocker{values[0], values[1], values[2]};
}

}  // namespace seqc::compiler
