// The keys each map of a choreography file may hold, as the front end checks them (an unknown
// key is an error with "did you mean"): one table per kind of map, so that the checks and the
// tools that offer keys while a file is written (the language server's completion) read the
// same lists.
#pragma once

#include <array>
#include <string_view>

namespace seqc::compiler {

// A servo controller's file, at the top level.
inline constexpr std::array<std::string_view, 12> kServoFileKeys = {
    "robot",  "music", "tempo",    "meter",    "resolution", "tolerance",
    "groups", "poses", "sections", "sequence", "name",       "description"};
// `robot:` written as a map, and one servo definition in its `servos`.
inline constexpr std::array<std::string_view, 5> kRobotKeys = {"profile", "servos", "mirror", "arm",
                                                               "controller"};
inline constexpr std::array<std::string_view, 6> kServoDefinitionKeys = {
    "id", "min", "max", "home", "max_speed", "max_accel"};
// `music:`.
inline constexpr std::array<std::string_view, 5> kMusicKeys = {"file", "downbeat", "tempo", "meter",
                                                               "changes"};
// A section written as `{params, steps}`.
inline constexpr std::array<std::string_view, 2> kSectionKeys = {"params", "steps"};
// The steps every robot kind shares.
inline constexpr std::array<std::string_view, 3> kRepeatStepKeys = {"repeat", "do", "at"};
inline constexpr std::array<std::string_view, 2> kIncludeStepKeys = {"include", "at"};
inline constexpr std::array<std::string_view, 3> kSectionStepKeys = {"section", "with", "at"};
inline constexpr std::array<std::string_view, 2> kTogetherStepKeys = {"together", "at"};
// The servo controllers' own steps, and a `through` waypoint.
inline constexpr std::array<std::string_view, 8> kMoveStepKeys = {
    "move", "time", "ease", "steps", "tolerance", "elbow", "path", "at"};
inline constexpr std::array<std::string_view, 2> kWaitStepKeys = {"wait", "at"};
inline constexpr std::array<std::string_view, 3> kThroughStepKeys = {"through", "tolerance", "at"};
inline constexpr std::array<std::string_view, 2> kMirrorStepKeys = {"mirror", "at"};
inline constexpr std::array<std::string_view, 2> kWaypointKeys = {"pose", "time"};

}  // namespace seqc::compiler
