// A move's `tip:` in millimetres: the joint positions inverse kinematics gives for the claw's tip
// (targets/servo_controller/arm_ik.hpp), rounded to whole units and checked against the servos'
// limits, so that the move goes on as an ordinary move of the joint servos; and the tip of every
// move of the joints checked against the table at every millisecond (tip_depth.hpp).
#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "base/units.hpp"
#include "compiler/program/arm_kinematics.hpp"
#include "compiler/targets/servo_controller/arm_ik.hpp"
#include "compiler/targets/servo_controller/servo_lowering_state.hpp"
#include "compiler/targets/servo_controller/tip_depth.hpp"
#include "compiler/targets/servo_controller/tip_line.hpp"
#include "compiler/targets/servo_controller/tip_text.hpp"
#include "protocol/lsc/group_download.hpp"

namespace seqc::compiler {
namespace {

// "150mm", "+20mm", "-5.5mm": the amount and whether a sign was written; nullopt if malformed.
std::optional<double> parse_length(std::string_view text, bool& signed_) {
  signed_ = !text.empty() && (text.front() == '+' || text.front() == '-');
  if (text.size() < 3 || text.substr(text.size() - 2) != "mm") return std::nullopt;
  text.remove_suffix(2);
  const bool negative = !text.empty() && text.front() == '-';
  if (signed_) text.remove_prefix(1);
  double v = 0;
  if (!parse_decimal(text, v)) return std::nullopt;
  return negative ? -v : v;
}

}  // namespace

bool ServoLowering::tip_entries(const YamlNode& step, const YamlNode& target,
                                std::vector<PositionEntry>& entries, TipTarget& placed) {
  const YamlNode& tip = *target.find("tip");
  if (!robot_.info.arm) {
    reporter_.error(tip.location, "'tip' needs the arm's geometry, and robot '" +
                                      robot_.info.profile +
                                      "' has none; give it with 'robot: {arm: ...}'");
    return false;
  }
  const ArmGeometry& arm = *robot_.info.arm;
  bool ok = true;
  std::array<double, 3> point{};
  bool relative = false;
  if (tip.is_map()) {
    // The named form is always absolute: a sign is only the coordinate's sign.
    if (!reporter_.check_keys(tip, {"x", "y", "z"}, "in 'tip'")) ok = false;
    const char* names[] = {"x", "y", "z"};
    for (std::size_t i = 0; i < 3; ++i) {
      const YamlNode* item = tip.find(names[i]);
      if (item == nullptr) {
        reporter_.error(tip.location, std::string("'tip' needs '") + names[i] +
                                          "' as well, e.g. 'tip: {x: 150mm, y: -80mm, z: 40mm}'");
        ok = false;
        continue;
      }
      bool sign = false;
      const std::optional<double> v =
          item->is_scalar() ? parse_length(item->scalar, sign) : std::nullopt;
      if (!v) {
        reporter_.error(item->location,
                        "a tip coordinate is a length in millimetres such as 150mm or -80mm");
        ok = false;
        continue;
      }
      point[i] = *v;
    }
  } else if (!tip.is_sequence() || tip.items.size() != 3) {
    reporter_.error(tip.location,
                    "'tip' takes [x, y, z] in millimetres, e.g. 'tip: [150mm, 0mm, 80mm]', or "
                    "with signs to move from where the tip is, e.g. 'tip: [+20mm, 0mm, 0mm]', "
                    "or names them for an absolute point, e.g. 'tip: {x: 150mm, y: -80mm, z: "
                    "40mm}'");
    ok = false;
  } else {
    // A coordinate without a sign but not 0 in a point that another's sign makes relative: most
    // likely meant as an absolute point (one with a negative coordinate needs the named form).
    const YamlNode* unsigned_offset = nullptr;
    for (std::size_t i = 0; i < 3; ++i) {
      bool sign = false;
      const YamlNode& item = tip.items[i];
      const std::optional<double> v =
          item.is_scalar() ? parse_length(item.scalar, sign) : std::nullopt;
      if (!v) {
        reporter_.error(item.location,
                        "a tip coordinate is a length in millimetres such as "
                        "150mm or +20mm");
        ok = false;
        continue;
      }
      point[i] = *v;
      relative = relative || sign;
      if (!sign && *v != 0 && unsigned_offset == nullptr) unsigned_offset = &item;
    }
    if (ok && relative && unsigned_offset != nullptr) {
      const YamlNode& item = *unsigned_offset;
      reporter_.warning(
          item.location,
          fmt::format("'{}' has no sign, but a sign elsewhere in this tip makes the whole point "
                      "relative, so it moves the tip by {} too; write '+{}', or name the "
                      "coordinates for an absolute point: 'tip: {{x: {}, y: {}, z: {}}}'",
                      item.scalar, item.scalar, item.scalar, tip.items[0].scalar,
                      tip.items[1].scalar, tip.items[2].scalar));
    }
  }
  std::optional<double> pitch;
  if (const YamlNode* p = target.find("pitch")) {
    std::string_view text = p->is_scalar() ? std::string_view(p->scalar) : "";
    const bool negative = !text.empty() && text.front() == '-';
    if (negative || (!text.empty() && text.front() == '+')) text.remove_prefix(1);
    double v = 0;
    if (text.size() > 3 && text.substr(text.size() - 3) == "deg" &&
        parse_decimal(text.substr(0, text.size() - 3), v)) {
      pitch = negative ? -v : v;
    } else {
      reporter_.error(p->location,
                      "'pitch' is the hand's angle in degrees (0deg up, 90deg "
                      "level, 180deg down), e.g. 'pitch: 180deg'");
      ok = false;
    }
  }
  bool elbow_up = true;
  const YamlNode* elbow = step.find("elbow");
  if (const YamlNode* inside = target.find("elbow");
      inside != nullptr && inside->is_scalar() &&
      (inside->scalar == "up" || inside->scalar == "down")) {
    if (elbow != nullptr) {
      reporter_.error(inside->location,
                      "'elbow' is given twice, in the move and beside it; keep one");
      ok = false;
    }
    elbow = inside;
  }
  if (const YamlNode* e = elbow) {
    if (e->is_scalar() && (e->scalar == "up" || e->scalar == "down")) {
      elbow_up = e->scalar == "up";
    } else {
      reporter_.error(e->location, "'elbow' is up or down");
      ok = false;
    }
  }
  if (mirrored_) {
    reporter_.error(tip.location, "a 'tip' move cannot be mirrored; give the joints instead");
    ok = false;
  }
  const ArmJoint* joints[] = {&arm.base, &arm.shoulder, &arm.elbow, &arm.wrist};
  std::size_t joint_servo[4] = {};
  for (std::size_t j = 0; j < 4; ++j) {
    auto it = robot_.names.find(joints[j]->servo);
    if (it == robot_.names.end()) {
      reporter_.error(tip.location, "the arm's joint servo '" + joints[j]->servo +
                                        "' is not a servo of this robot");
      return false;
    }
    joint_servo[j] = it->second;
    for (const PositionEntry& e : entries) {
      if (e.output != joint_servo[j]) continue;
      reporter_.error(e.at, "'" + joints[j]->servo +
                                "' is placed by 'tip' in this move; leave it out or drop 'tip'");
      ok = false;
    }
  }
  if (!ok) return false;

  // Where the tip is now: needed to move from it, and for the pitch it keeps.
  const YamlNode* path = step.find("path");
  const bool line = path != nullptr && path->is_scalar() && path->scalar == "line";
  if (relative || !pitch || line) {
    for (std::size_t j = 0; j < 4; ++j) {
      if (pos_[joint_servo[j]]) continue;
      reporter_.error(tip.location, "'" + joints[j]->servo +
                                        "' has no known position yet, so the tip's " +
                                        (relative || line ? "position" : "pitch") +
                                        " is unknown; move the arm to absolute positions first");
      return false;
    }
  }
  auto now_position = [&](std::string_view servo) {
    auto it = robot_.names.find(servo);
    return it != robot_.names.end() && pos_[it->second] ? static_cast<double>(*pos_[it->second])
                                                        : 0.0;
  };
  auto angle_of = [&](std::size_t j) {
    return joints[j]->sign * (now_position(joints[j]->servo) - joints[j]->zero) *
           arm.degrees_per_unit;
  };
  if (relative) {
    const std::array<double, 3> from = compiler::arm_points(arm, now_position).tip;
    for (std::size_t i = 0; i < 3; ++i) point[i] += from[i];
  }
  if (!pitch) pitch = angle_of(1) + angle_of(2) + angle_of(3);
  const std::string where =
      point_text(point) + fmt::format(" at pitch {:g}deg", std::round(*pitch * 10) / 10);
  if (point[2] < 0) {
    reporter_.error(tip.location, fmt::format("the tip {} would be {:.0f} mm below the table",
                                              point_text(point), -point[2]));
    return false;
  }
  const double base_now = pos_[joint_servo[0]] ? angle_of(0) : 0.0;
  const compiler::ArmSolution solution =
      compiler::solve_arm(arm, point, *pitch, elbow_up, base_now);
  if (!solution.angles) {
    if (solution.needed > solution.reach) {
      reporter_.error(
          tip.location,
          fmt::format("the tip {} is {:.0f} mm beyond the arm's reach of {:g} mm (the wrist, "
                      "{:g} mm back from the tip, is {:.0f} mm from the shoulder)",
                      where, solution.needed - solution.reach, solution.reach, arm.hand,
                      solution.needed));
    } else {
      reporter_.error(tip.location,
                      fmt::format("the tip {} puts the wrist {:.0f} mm from the shoulder, nearer "
                                  "than the arm can fold ({:g} mm)",
                                  where, solution.needed, solution.reach));
    }
    return false;
  }
  const double angles[] = {solution.angles->base, solution.angles->shoulder, solution.angles->elbow,
                           solution.angles->wrist};
  for (std::size_t j = 0; j < 4; ++j) {
    const ServoInfo& servo = robot_.info.servos[joint_servo[j]];
    const long long units =
        std::llround(joints[j]->zero + joints[j]->sign * angles[j] / arm.degrees_per_unit);
    if (units < servo.min || units > servo.max) {
      const long long over = units > servo.max ? units - servo.max : servo.min - units;
      reporter_.error(
          tip.location,
          fmt::format("the tip {} needs '{}' at {} ({:.1f}deg), {} {} its {} {}", where, servo.name,
                      units, angles[j], over, units > servo.max ? "above" : "below",
                      units > servo.max ? "max" : "min",
                      units > servo.max ? servo.max : servo.min));
      ok = false;
      continue;
    }
    PositionEntry e;
    e.output = joint_servo[j];
    e.written = "tip";
    e.value.amount = static_cast<double>(units);
    e.at = tip.location;
    entries.push_back(std::move(e));
  }
  placed.point = point;
  placed.pitch = *pitch;
  placed.elbow_up = elbow_up;
  for (std::size_t j = 0; j < 4; ++j) placed.joints[j] = joint_servo[j];
  return ok;
}

namespace {

// The servos of the arm's base, shoulder, elbow and wrist; nullopt without a geometry or when
// one is not a servo of the robot (tip_entries() reports that where a tip is asked for).
std::optional<std::array<std::size_t, 4>> arm_joint_servos(const Robot& robot) {
  if (!robot.info.arm) return std::nullopt;
  const ArmGeometry& arm = *robot.info.arm;
  std::array<std::size_t, 4> out{};
  const ArmJoint* joints[] = {&arm.base, &arm.shoulder, &arm.elbow, &arm.wrist};
  for (std::size_t j = 0; j < 4; ++j) {
    auto it = robot.names.find(joints[j]->servo);
    if (it == robot.names.end()) return std::nullopt;
    out[j] = it->second;
  }
  return out;
}

}  // namespace

void ServoLowering::record_arm_move(const std::function<bool(std::size_t)>& moves, ExactMs start,
                                    ExactMs end, Location at, bool tip_end,
                                    double line_tolerance_mm) {
  const auto joints = arm_joint_servos(robot_);
  if (!joints || std::none_of(joints->begin(), joints->end(), moves)) return;
  arm_moves_.push_back({start, end, at, tip_end, line_tolerance_mm});
}

void ServoLowering::check_tip_depth() {
  const auto joints = arm_joint_servos(robot_);
  if (!joints) return;
  for (const TipDip& d : find_tip_dips(*robot_.info.arm, *joints, timeline_, arm_moves_)) {
    // A warning (an error with --strict): the end points a file names are errors below the
    // table, but between them the dip is the joints' path, which the file may well mean.
    reporter_.warning(d.at,
                      fmt::format("the tip goes {:.1f} mm below the table at {:.3f} s "
                                  "(deepest, {}), for {:.0f} ms",
                                  d.depth_mm, d.at_ms / 1000, point_text(d.point), d.below_ms));
  }
}

}  // namespace seqc::compiler
