#include "compiler/frontend/profiles.hpp"

#include "base/units.hpp"
#include "protocol/lsc/lsc_messages.hpp"
#include "protocol/lsc6/lsc6_messages.hpp"

namespace seqc::compiler {
namespace {

// Facts from docs/protocol/servo-controller.md ("Units and ranges"). Rated speeds are the stock
// servos' datasheet figures at 7.4 V: Hiwonder LX-15D bus servo (the xArm's), 0.16 s per 60
// degrees; the LD-1501MG / LDX-218 class of PWM servos sold with LSC boards, 0.16 s per 60
// degrees. 375 deg/s is 1562.5 units/s on the xArm (1000 units over 240 deg) and 4166.7 us/s on
// a PWM servo (2000 us over 180 deg).
constexpr double kRatedDegreesPerSecond = 60 / 0.16;
// The xArm 1S's links, from public xArm 1S URDF descriptions, which agree on an upper arm and a
// forearm of about 97 and 96 mm: for one, github.com/Werewolf-Leader/xArm_1s-Description-Package
// (urdf/xarm.xacro) puts the elbow axis 96.4 mm from the shoulder axis and the wrist-pitch axis
// 58.3 + 37.4 = 95.7 mm from the elbow. The base height and the hand (wrist axis to the claw's
// tip) are measurements. Shoulder, elbow and wrist servos are mounted so that a larger position
// tilts the arm back towards the base axis.
// A function's static, so the table (itself a function's static) never sees it uninitialised.
const ArmGeometry& xarm_arm() {
  static const ArmGeometry arm = {.base_height = 72,
                                  .upper_arm = 97,
                                  .forearm = 96,
                                  .hand = 150,
                                  .base = {"base", 500, 1},
                                  .shoulder = {"shoulder", 500, -1},
                                  .elbow = {"elbow", 500, -1},
                                  .wrist = {"wrist_pitch", 500, -1},
                                  .degrees_per_unit = 1,  // robot_from_profile sets the profile's
                                  .claw = "claw"};
  return arm;
}
// The LeArm's links: upper arm 10.43 cm, forearm 8.9 cm and wrist-pitch axis to the gripper's
// tip 17.7 cm are the constants of Hiwonder's own LeArm kinematics (LINKAGE_2..4 in the
// Kinematics.hpp of its 2024 LeArm controller firmware). That firmware measures heights from its
// own origin 28.9 mm below the shoulder axis, not from the table, so the base height is a public
// measurement of the arm instead: 85 mm from the base plate to the shoulder axis (the LeArm's
// arm_attributes.yaml in github.com/thomazach/LeArm). The same firmware's servo map is the
// xArm's (6 base, 5 shoulder, 4 elbow, 3 wrist pitch, 2 wrist roll, 1 gripper) and its joint
// angles are 90 degrees (1500 us) with the arm straight up: a longer pulse turns the base
// counter-clockwise and tilts the shoulder forward, and tilts the elbow and the wrist back.
const ArmGeometry& learm_arm() {
  static const ArmGeometry arm = {.base_height = 85,
                                  .upper_arm = 104.3,
                                  .forearm = 89,
                                  .hand = 177,
                                  .base = {"base", 1500, 1},
                                  .shoulder = {"shoulder", 1500, 1},
                                  .elbow = {"elbow", 1500, -1},
                                  .wrist = {"wrist_pitch", 1500, -1},
                                  .degrees_per_unit = 1,  // robot_from_profile sets the profile's
                                  .claw = "claw"};
  return arm;
}
const std::vector<RobotProfile>& profiles() {
  // One row per profile reads better than one field per line.
  // clang-format off
  static const std::vector<RobotProfile> table = {
      // xArm bus servos: 0-1000 over 0-240 degrees, 500 = centre, ids 1-6.
      {"xarm", RobotKind::ServoController, "xarm", 1, 6, 0, 1000, 500, 0.0, 1000.0 / 240.0,
       {{"claw", 1},
        {"wrist_roll", 2},
        {"wrist_pitch", 3},
        {"elbow", 4},
        {"shoulder", 5},
        {"base", 6}},
       "servo", kRatedDegreesPerSecond * 1000.0 / 240.0, lsc::kMaxActions, &xarm_arm()},
      // Any LewanSoul/Hiwonder bus servos on the controller (humanoids, hexapods, the .d6a files
      // of Hiwonder's tools): ids 1-32 named s1..s32, the xArm's units and speed.
      {"bus", RobotKind::ServoController, "xarm", 1, 32, 0, 1000, 500, 0.0, 1000.0 / 240.0, {},
       "s", kRatedDegreesPerSecond * 1000.0 / 240.0},
      // PWM boards: 500-2500 us, 1500 = neutral; 0-180 degrees is the usual hobby-servo travel.
      {"lsc-16", RobotKind::ServoController, "xarm", 0, 15, 500, 2500, 1500, 500.0, 2000.0 / 180.0, {},
       "ch", kRatedDegreesPerSecond * 2000.0 / 180.0},
      {"lsc-32", RobotKind::ServoController, "xarm", 0, 31, 500, 2500, 1500, 500.0, 2000.0 / 180.0, {},
       "ch", kRatedDegreesPerSecond * 2000.0 / 180.0},
      // LSC-6 / LeArm: six PWM outputs that its firmware numbers 1-6 (docs/protocol/lsc-6.md);
      // uploads use that board's own dialect.
      {"lsc-6", RobotKind::ServoController, "lsc6", 1, 6, 500, 2500, 1500, 500.0, 2000.0 / 180.0, {},
       "ch", kRatedDegreesPerSecond * 2000.0 / 180.0, lsc6::kMaxActions},
      // The LeArm: the LSC-6 board with the arm's servos named as on the xArm, and its geometry.
      {"learm", RobotKind::ServoController, "lsc6", 1, 6, 500, 2500, 1500, 500.0, 2000.0 / 180.0,
       {{"claw", 1},
        {"wrist_roll", 2},
        {"wrist_pitch", 3},
        {"elbow", 4},
        {"shoulder", 5},
        {"base", 6}},
       "ch", kRatedDegreesPerSecond * 2000.0 / 180.0, lsc6::kMaxActions, &learm_arm()},
      // Yahboom Raspblock car board: servos 1-4 at 500-2500 us; its gimbal and rocker are
      // outputs of the board itself (targets/raspblock/raspblock_lowering.cpp).
      {"raspblock", RobotKind::Raspblock, "raspblock", 1, 4, 500, 2500, 1500, 500.0, 2000.0 / 180.0, {},
       "servo"},
  };
  // clang-format on
  return table;
}

}  // namespace

std::string_view position_unit(std::string_view profile) {
  for (std::string_view pwm : {"lsc-16", "lsc-32", "lsc-6", "learm"}) {
    if (profile == pwm) return "us";
  }
  return "units";
}

const RobotProfile* find_profile(std::string_view name) {
  for (const RobotProfile& p : profiles()) {
    if (p.name == name) return &p;
  }
  return nullptr;
}

std::vector<std::string> profile_names() {
  std::vector<std::string> names;
  for (const RobotProfile& p : profiles()) names.emplace_back(p.name);
  return names;
}

std::string profile_list() {
  std::string out;
  for (const std::string& name : profile_names()) out += (out.empty() ? "" : ", ") + name;
  return out;
}

RobotInfo robot_from_profile(const RobotProfile& profile) {
  RobotInfo robot;
  robot.profile = std::string(profile.name);
  robot.kind = profile.kind;
  robot.board = std::string(profile.board);
  for (int id = profile.first_id; id <= profile.last_id; ++id) {
    ServoInfo s;
    s.id = static_cast<std::uint8_t>(id);
    s.name = std::string(profile.default_prefix) + std::to_string(id);
    for (const auto& [name, named_id] : profile.names) {
      if (named_id == id) s.name = std::string(name);
    }
    s.min = profile.min;
    s.max = profile.max;
    s.home = profile.home;
    if (profile.rated_speed > 0) s.max_speed = profile.rated_speed;
    robot.servos.push_back(std::move(s));
  }
  if (profile.arm != nullptr) {
    robot.arm = *profile.arm;
    robot.arm->degrees_per_unit = 1 / profile.units_per_degree;
  }
  return robot;
}

std::size_t group_capacity(const RobotProfile* profile) {
  return profile != nullptr ? profile->max_actions : lsc::kMaxActions;
}

std::size_t stored_groups(const RobotProfile* profile) {
  return profile != nullptr && profile->board == "lsc6" ? lsc6::kGroups : lsc::kAllGroups;
}

std::string group_capacity_text(const RobotProfile* profile) {
  // Counts in messages carry thousands separators: "action 1,021".
  auto count = [](std::size_t n) { return format_grouped(static_cast<long long>(n)); };
  const std::size_t cap = group_capacity(profile);
  const std::string holds =
      cap == lsc::kMaxActions
          ? "a group holds at most 1,020 (4 blocks of 255)"
          : "a group on the " + std::string(profile->name) + " holds at most " + count(cap);
  return holds + ", and this step makes action " + count(cap + 1);
}

}  // namespace seqc::compiler
