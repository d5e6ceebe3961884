#include "compiler/frontend/robot_section.hpp"

#include <cmath>

#include "base/units.hpp"
#include "compiler/frontend/key_tables.hpp"

namespace seqc::compiler {
namespace {

bool is_identifier(std::string_view s) {
  if (s.empty()) return false;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const char c = s[i];
    const bool alpha = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_';
    const bool digit = c >= '0' && c <= '9';
    if (!(alpha || (i > 0 && digit))) return false;
  }
  return true;
}

const RobotProfile* profile_named(const YamlNode& value, Reporter& reporter) {
  if (!value.is_scalar()) {
    reporter.error(value.location, "the robot profile must be a name: one of " + profile_list());
    return nullptr;
  }
  const RobotProfile* profile = find_profile(value.scalar);
  if (profile == nullptr) {
    reporter.unknown(value.location, "robot", value.scalar, profile_names(), {},
                     "robots: " + profile_list());
  }
  return profile;
}

std::string range_text(long long lo, long long hi) {
  return std::to_string(lo) + "-" + std::to_string(hi);
}

// One entry of `servos:`: either an id or a map of id/min/max/home/max_speed.
void parse_servo(Robot& robot, const YamlNode& key, const YamlNode& value,
                 std::map<std::uint8_t, Location>& defined_ids, Reporter& reporter) {
  const RobotProfile& profile = *robot.profile;
  const std::string& name = key.scalar;
  if (!is_identifier(name)) {
    reporter.error(key.location, "servo name '" + name +
                                     "' must start with a letter or '_' and contain only "
                                     "letters, digits and '_'");
    return;
  }
  const YamlNode* id_node = nullptr;
  if (value.is_scalar()) {
    id_node = &value;
  } else if (value.is_map()) {
    reporter.check_keys(value, kServoDefinitionKeys, "in a servo definition");
    id_node = value.find("id");
  } else {
    reporter.error(value.location, "servo '" + name +
                                       "' must be an id (e.g. 3) or a map with id, min, max, "
                                       "home, max_speed, max_accel");
    return;
  }

  auto existing = robot.names.find(name);
  std::optional<std::size_t> index;
  if (id_node != nullptr) {
    auto id = parse_integer(*id_node, profile.first_id, profile.last_id,
                            "servo id on " + std::string(profile.name), reporter);
    if (!id) return;
    const auto id8 = static_cast<std::uint8_t>(*id);
    auto [it, inserted] = defined_ids.emplace(id8, id_node->location);
    if (!inserted) {
      reporter.error(id_node->location, "servo id " + std::to_string(*id) +
                                            " is already defined at line " +
                                            std::to_string(it->second.line));
      return;
    }
    index = static_cast<std::size_t>(id8 - profile.first_id);
    if (existing != robot.names.end() && existing->second != *index) {
      reporter.error(key.location, "'" + name + "' is servo " +
                                       std::to_string(robot.info.servos[existing->second].id) +
                                       " on " + std::string(profile.name) +
                                       "; give a new name to servo " + std::to_string(*id));
      return;
    }
    robot.info.servos[*index].name = name;
    robot.names[name] = *index;
  } else if (existing != robot.names.end()) {
    index = existing->second;
  } else {
    reporter.error(key.location, "servo '" + name + "' needs an 'id' (" +
                                     std::string(profile.name) + " ids are " +
                                     range_text(profile.first_id, profile.last_id) + ")");
    return;
  }
  if (!value.is_map()) return;

  ServoInfo& servo = robot.info.servos[*index];
  std::optional<long long> lo, hi, home;
  if (const YamlNode* n = value.find("min")) {
    lo = parse_integer(*n, profile.min, profile.max, "'min' on " + std::string(profile.name),
                       reporter);
  }
  if (const YamlNode* n = value.find("max")) {
    hi = parse_integer(*n, profile.min, profile.max, "'max' on " + std::string(profile.name),
                       reporter);
  }
  if (lo) servo.min = static_cast<int>(*lo);
  if (hi) servo.max = static_cast<int>(*hi);
  if ((value.find("min") && !lo) || (value.find("max") && !hi)) return;  // already reported
  if (servo.min >= servo.max) {
    reporter.error(value.location, "servo '" + name + "' has min " + std::to_string(servo.min) +
                                       " not below max " + std::to_string(servo.max));
    return;
  }
  if (const YamlNode* n = value.find("home")) {
    home = parse_integer(*n, servo.min, servo.max, "'home' within " + name + "'s limits", reporter);
    if (home) servo.home = static_cast<int>(*home);
  } else if (servo.home < servo.min || servo.home > servo.max) {
    reporter.error(value.location, "servo '" + name + "' limits " +
                                       range_text(servo.min, servo.max) +
                                       " exclude the profile's home " + std::to_string(servo.home) +
                                       "; give it a 'home'");
  }
  if (const YamlNode* n = value.find("max_speed")) {
    if (!n->is_scalar()) {
      reporter.error(n->location, "'max_speed' must be a speed such as 400/s or 90deg/s");
    } else if (auto speed = parse_speed(n->scalar); !speed) {
      reporter.error(n->location, speed.error().message);
    } else {
      servo.max_speed =
          speed->degrees ? speed->per_second * profile.units_per_degree : speed->per_second;
    }
  }
  if (const YamlNode* n = value.find("max_accel")) {
    // "2000/s2", "2000/s^2", "500deg/s2": device units (or degrees) per second squared.
    std::string_view text = n->is_scalar() ? std::string_view(n->scalar) : "";
    bool ok = false;
    for (std::string_view unit : {"/s^2", "/s2"}) {
      if (text.size() > unit.size() && text.substr(text.size() - unit.size()) == unit) {
        text.remove_suffix(unit.size());
        ok = true;
        break;
      }
    }
    const bool degrees = ok && text.size() > 3 && text.substr(text.size() - 3) == "deg";
    if (degrees) text.remove_suffix(3);
    double amount = 0;
    if (!ok || !parse_decimal(text, amount) || amount <= 0) {
      reporter.error(n->location,
                     "'max_accel' must be an acceleration such as 4000/s2 or 900deg/s2");
    } else {
      servo.max_accel = degrees ? amount * profile.units_per_degree : amount;
    }
  }
}

void parse_mirror(Robot& robot, const YamlNode& table, Reporter& reporter) {
  if (!table.is_map()) {
    reporter.error(table.location,
                   "'mirror' must be a map of left: right servo names, e.g. left_arm: right_arm");
    return;
  }
  robot.has_mirror_table = true;
  const std::vector<std::string> names = robot.name_list();
  std::map<std::size_t, Location> used;
  auto lookup = [&](const YamlNode& n) -> std::optional<std::size_t> {
    if (!n.is_scalar()) {
      reporter.error(n.location, "mirror entries pair two servo names");
      return std::nullopt;
    }
    auto it = robot.names.find(n.scalar);
    if (it == robot.names.end()) {
      reporter.unknown(n.location, "servo", n.scalar, names, "in the mirror table");
      return std::nullopt;
    }
    auto [u, fresh] = used.emplace(it->second, n.location);
    if (!fresh) {
      reporter.error(n.location, "servo '" + n.scalar + "' is already paired at line " +
                                     std::to_string(u->second.line));
      return std::nullopt;
    }
    return it->second;
  };
  for (const auto& [left, right] : table.entries) {
    auto l = lookup(left);
    if (l && right.is_scalar() && right.scalar == left.scalar) {  // a centre servo: reflect only
      robot.mirror[*l] = *l;
      continue;
    }
    auto r = lookup(right);
    if (!l || !r) continue;
    robot.mirror[*l] = *r;
    robot.mirror[*r] = *l;
  }
}

// A length in mm: "97" or "97mm", above 0 and at most 5000.
std::optional<double> parse_length(const YamlNode& value, std::string_view what,
                                   Reporter& reporter) {
  std::string_view text = value.is_scalar() ? std::string_view(value.scalar) : "";
  if (text.size() > 2 && text.substr(text.size() - 2) == "mm") text.remove_suffix(2);
  double mm = 0;
  if (text.empty() || !parse_decimal(text, mm) || mm <= 0 || mm > 5000) {
    reporter.error(value.location, "'" + std::string(what) +
                                       "' must be a length in mm above 0 (at most 5000), e.g. 97 "
                                       "or 97mm");
    return std::nullopt;
  }
  return mm;
}

// One entry of `arm: {joints: ...}`: {servo, zero, sign}.
void parse_joint(const Robot& robot, const YamlNode& key, const YamlNode& value, ArmJoint& joint,
                 Reporter& reporter) {
  if (!value.is_map()) {
    reporter.error(value.location, "joint '" + key.scalar +
                                       "' must be a map of servo, zero and sign, e.g. {servo: "
                                       "elbow, zero: 500, sign: -1}");
    return;
  }
  reporter.check_keys(value, {"servo", "zero", "sign"}, "in an arm joint");
  if (const YamlNode* n = value.find("servo")) {
    if (!n->is_scalar()) {
      reporter.error(n->location, "a joint's 'servo' must be a servo name");
    } else if (robot.names.find(n->scalar) == robot.names.end()) {
      reporter.unknown(n->location, "servo", n->scalar, robot.name_list(),
                       "for arm joint '" + key.scalar + "'");
    } else {
      joint.servo = robot.info.servos[robot.names.find(n->scalar)->second].name;
    }
  }
  if (const YamlNode* n = value.find("zero")) {
    if (auto zero =
            parse_integer(*n, robot.profile->min, robot.profile->max,
                          "a joint's 'zero' on " + std::string(robot.profile->name), reporter)) {
      joint.zero = static_cast<double>(*zero);
    }
  }
  if (const YamlNode* n = value.find("sign")) {
    if (n->is_scalar() && (n->scalar == "1" || n->scalar == "+1" || n->scalar == "-1")) {
      joint.sign = n->scalar == "-1" ? -1 : 1;
    } else {
      reporter.error(n->location, "a joint's 'sign' must be 1 or -1");
    }
  }
}

// `arm:` (docs/language.md, "The arm's geometry"): lengths in mm and the joints' servos, over the
// profile's built-in geometry when it has one.
void parse_arm(Robot& robot, const YamlNode& value, Reporter& reporter) {
  const RobotProfile& profile = *robot.profile;
  if (profile.kind != RobotKind::ServoController) {
    reporter.error(value.location,
                   "'arm' is for servo controllers; " + std::string(profile.name) + " has no arm");
    return;
  }
  if (!value.is_map()) {
    reporter.error(value.location,
                   "'arm' must be a map of base_height, upper_arm, forearm, hand (mm), joints and "
                   "claw");
    return;
  }
  const std::size_t errors = reporter.errors_reported();
  reporter.check_keys(value, {"base_height", "upper_arm", "forearm", "hand", "joints", "claw"},
                      "in 'arm'");
  ArmGeometry arm;
  if (robot.info.arm) {
    arm = *robot.info.arm;
  } else {
    arm.degrees_per_unit = 1 / profile.units_per_degree;
    for (ArmJoint* j : {&arm.base, &arm.shoulder, &arm.elbow, &arm.wrist}) {
      j->zero = profile.home;
    }
  }
  const std::pair<const char*, double*> lengths[] = {{"base_height", &arm.base_height},
                                                     {"upper_arm", &arm.upper_arm},
                                                     {"forearm", &arm.forearm},
                                                     {"hand", &arm.hand}};
  for (const auto& [name, field] : lengths) {
    if (const YamlNode* n = value.find(name)) {
      if (auto mm = parse_length(*n, name, reporter)) *field = *mm;
    }
  }
  if (const YamlNode* joints = value.find("joints")) {
    if (!joints->is_map()) {
      reporter.error(joints->location,
                     "'joints' must be a map of base, shoulder, elbow, wrist: {servo, zero, sign}");
    } else {
      reporter.check_keys(*joints, {"base", "shoulder", "elbow", "wrist"}, "in 'joints'");
      const std::pair<const char*, ArmJoint*> names[] = {{"base", &arm.base},
                                                         {"shoulder", &arm.shoulder},
                                                         {"elbow", &arm.elbow},
                                                         {"wrist", &arm.wrist}};
      for (const auto& [key, def] : joints->entries) {
        for (const auto& [name, joint] : names) {
          if (key.scalar == name) parse_joint(robot, key, def, *joint, reporter);
        }
      }
    }
  }
  if (const YamlNode* n = value.find("claw")) {
    if (!n->is_scalar() || robot.names.find(n->scalar) == robot.names.end()) {
      reporter.unknown(n->location, "servo", n->is_scalar() ? n->scalar : "", robot.name_list(),
                       "for the arm's claw");
    } else {
      arm.claw = robot.info.servos[robot.names.find(n->scalar)->second].name;
    }
  }
  if (reporter.errors_reported() != errors) return;
  std::string missing;
  for (const auto& [name, field] : lengths) {
    if (*field <= 0) missing += std::string(missing.empty() ? "" : ", ") + name;
  }
  for (const auto& [name, joint] : {std::pair<const char*, const ArmJoint*>{"base", &arm.base},
                                    {"shoulder", &arm.shoulder},
                                    {"elbow", &arm.elbow},
                                    {"wrist", &arm.wrist}}) {
    if (joint->servo.empty()) {
      missing += std::string(missing.empty() ? "" : ", ") + "joints: " + name + ": servo";
    }
  }
  if (!missing.empty()) {
    reporter.error(value.location, "'arm' on " + std::string(profile.name) +
                                       " (no built-in geometry) needs " + missing);
    return;
  }
  robot.info.arm = arm;
}

}  // namespace

std::vector<std::string> Robot::name_list() const {
  std::vector<std::string> out;
  for (const auto& [name, index] : names) out.push_back(name);
  return out;
}

double Robot::degrees_to_units(double degrees, bool relative) const {
  return (relative ? 0.0 : profile->degree_zero) + degrees * profile->units_per_degree;
}

std::optional<long long> parse_integer(const YamlNode& value, long long lo, long long hi,
                                       std::string_view what, Reporter& reporter) {
  const std::string range = range_text(lo, hi);
  if (!value.is_scalar()) {
    reporter.error(value.location, std::string(what) + " must be a whole number " + range);
    return std::nullopt;
  }
  const std::string& s = value.scalar;
  long long v = 0;
  bool ok = !s.empty() && s.size() <= 12;
  for (char c : s) {
    ok = ok && c >= '0' && c <= '9';
    if (ok) v = v * 10 + (c - '0');
  }
  if (!ok) {
    reporter.error(value.location,
                   "'" + s + "' is not a whole number; " + std::string(what) + " is " + range);
    return std::nullopt;
  }
  if (v < lo || v > hi) {
    reporter.error(value.location, std::string(what) + " must be " + range + ", not " + s);
    return std::nullopt;
  }
  return v;
}

std::optional<Robot> parse_robot(const YamlNode& value, Reporter& reporter) {
  Robot robot;
  const YamlNode* profile_node = &value;
  if (value.is_map()) {
    reporter.check_keys(value, kRobotKeys, "in 'robot'");
    profile_node = value.find("profile");
    if (profile_node == nullptr) {
      reporter.error(value.location, "'robot' needs a 'profile': one of " + profile_list());
      return std::nullopt;
    }
  }
  robot.profile = profile_named(*profile_node, reporter);
  if (robot.profile == nullptr) return std::nullopt;
  robot.info = robot_from_profile(*robot.profile);
  robot.controller = robot.profile->controller;
  for (std::size_t i = 0; i < robot.info.servos.size(); ++i) {
    robot.names[robot.info.servos[i].name] = i;
  }
  auto finish = [&robot]() {
    for (std::size_t i = 0; i < robot.info.servos.size(); ++i) {
      const std::string default_name =
          std::string(robot.profile->default_prefix) + std::to_string(robot.info.servos[i].id);
      if (robot.info.servos[i].name != default_name) robot.home_servos.push_back(i);
    }
    if (robot.home_servos.empty()) {
      for (std::size_t i = 0; i < robot.info.servos.size(); ++i) robot.home_servos.push_back(i);
    }
    return robot;
  };
  if (!value.is_map()) return finish();

  if (const YamlNode* servos = value.find("servos")) {
    if (servos->is_map()) {
      std::map<std::uint8_t, Location> defined_ids;
      for (const auto& [key, def] : servos->entries) {
        parse_servo(robot, key, def, defined_ids, reporter);
      }
      if (!defined_ids.empty()) robot.info.highest_defined_id = defined_ids.rbegin()->first;
    } else if (servos->kind != YamlNode::Kind::Null) {
      reporter.error(servos->location, "'servos' must be a map of name: id or name: {id: ...}");
    }
  }
  if (const YamlNode* mirror = value.find("mirror")) parse_mirror(robot, *mirror, reporter);
  if (robot.info.arm) {
    // The built-in geometry names the profile's servos; the file may have renamed them.
    for (ArmJoint* j : {&robot.info.arm->base, &robot.info.arm->shoulder, &robot.info.arm->elbow,
                        &robot.info.arm->wrist}) {
      if (auto it = robot.names.find(j->servo); it != robot.names.end()) {
        j->servo = robot.info.servos[it->second].name;
      }
    }
    if (auto it = robot.names.find(robot.info.arm->claw); it != robot.names.end()) {
      robot.info.arm->claw = robot.info.servos[it->second].name;
    }
  }
  if (const YamlNode* arm = value.find("arm")) parse_arm(robot, *arm, reporter);
  if (const YamlNode* c = value.find("controller")) {
    if (robot.info.kind != RobotKind::ServoController) {
      reporter.error(c->location, "'controller' is for servo controllers; " +
                                      std::string(robot.profile->name) + " stores no actions");
    } else if (const std::optional<ControllerModel> model =
                   c->is_scalar() ? controller_model_named(c->scalar) : std::nullopt) {
      robot.controller = *model;
    } else if (c->is_scalar()) {
      reporter.unknown(c->location, "controller model", c->scalar,
                       {"straight-line", "rounds", "truncates"}, {},
                       "straight-line: the exact line between whole-unit targets; rounds or "
                       "truncates: that line rounded or truncated to whole units");
    } else {
      reporter.error(c->location,
                     "'controller' is one of straight-line, rounds or truncates, not a list "
                     "or map");
    }
  }
  return finish();
}

std::optional<RobotInfo> robot_of_text(const std::string& path, const std::string& text,
                                       SourceManager& sources, Diagnostics& diags) {
  const std::uint32_t file = sources.add(path, text);
  const std::optional<YamlNode> root = load_yaml(sources, file, diags, YamlLimits{});
  if (!root) return std::nullopt;
  Reporter reporter(diags);
  const YamlNode* robot = root->is_map() ? root->find("robot") : nullptr;
  if (robot == nullptr) {
    report_missing_robot(*root, path, reporter);
    return std::nullopt;
  }
  std::optional<Robot> parsed = parse_robot(*robot, reporter);
  if (!parsed || diags.has_errors()) return std::nullopt;
  return parsed->info;
}

void report_missing_robot(const YamlNode& root, const std::string& path, Reporter& reporter) {
  for (const YamlEntry& entry : root.entries) {
    if (entry.first.scalar != "performers") continue;
    reporter.error(
        entry.first.location,
        "this is a show file (it has 'performers'), not one robot's choreography",
        Reporter::Note{entry.first.location, "a show runs with 'seqc show " + path + "'"});
    return;
  }
  reporter.error(root.location,
                 "missing 'robot': name the robot this file is for (" + profile_list() + ")");
}

std::optional<std::string> included_robot_name(const YamlNode& value, Reporter& reporter) {
  if (!value.is_scalar()) {
    reporter.error(value.location,
                   "an included file may only name its robot (robot: xarm); define servos and "
                   "the mirror table in the main file");
    return std::nullopt;
  }
  if (profile_named(value, reporter) == nullptr) return std::nullopt;
  return value.scalar;
}

}  // namespace seqc::compiler
