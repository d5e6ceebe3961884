// A `path: line` tip move: the claw's tip in a straight line from where it is to a target, the
// hand's pitch interpolated alike, the step's easing applied to the distance along the line.
// The controller moves each joint in a straight line between whole-unit targets, so the line is
// followed by choosing action boundaries (whole milliseconds, each action at least the board's
// minimum) and whole-unit joint targets at them such that the tip, by forward kinematics of the
// joints as the controller moves them (program/arm_kinematics.hpp, under the board's
// ControllerModel), stays within the tolerance of the line's point at every millisecond.
//
// The search is a breadth-first dynamic program over (boundary, joint targets): a boundary's
// candidate targets are the floor/ceil combinations of the exact inverse kinematics there
// (targets/servo_controller/arm_ik.hpp) that are within the servos' limits and put the tip
// within the tolerance; an action joins two candidates when every millisecond between them
// passes. Layers are counted in actions, so the first layer that reaches the end has the fewest
// actions among the boundaries searched. Boundaries are every millisecond for a move of up to
// kFullGridMs and an even grid of about kGridPoints points beyond (no coarser than a quarter of
// the longest action), and an action stops being
// extended once kGiveUp grid points in a row past the minimum fail (a longer one could pass
// again only by luck of rounding). The move's other servos share the actions (each action names
// every servo of the move, so the fitter keeps them as they are): their targets are their eased
// curves rounded at the boundaries, and an action passes only if they too stay within their
// tolerance at every millisecond. Another track's servo whose curve runs within the line's time
// may be one of them too (OtherServo::curve), so that the fitter need not cut the joints'
// pieces to fit it.
//
// So that a line of minutes or hours costs its actions rather than its milliseconds, a line
// longer than a minute is checked for the table, the reach and the limits (and its error
// measured) at about 60,000 evenly spaced instants and its grid points rather than at every
// millisecond, and an action longer than 2 s at 128 evenly spaced instants against the
// tolerance less 5 % (its tip moves far less than that between them).
//
// Other servos' segment boundaries inside the line (another track of a `together` block) are
// action boundaries for every servo (compiler/fitting/fitter.hpp), so the caller may name them
// in `forced_ms`: the line's actions then end at each of them too, with whole-unit joint targets
// chosen like any other boundary's, and no action spans one. A second search of a line already
// fitted pins its end (`end_joints`), so that the steps after it, which started from there, stay
// as they were. Pure: no diagnostics here; the caller words the problems.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "compiler/fitting/fitter.hpp"
#include "compiler/program/arm_geometry.hpp"
#include "compiler/program/controller_model.hpp"
#include "compiler/timeline/easing.hpp"

namespace seqc::compiler {

using Joints = std::array<int, 4>;  // base, shoulder, elbow, wrist, device units
using Point = std::array<double, 3>;

// Another servo of the same move (the claw, the wrist's roll): it follows the step's easing from
// `from` to `to` in device units, within `tolerance` units, on the line's actions. Or one of
// another track whose curve runs during the line: `curve` holds its segments in time order, from
// the one in force at start_ms to the one in force at end_ms, so that where it is meant to be at
// any millisecond of the line is the value of the last of them starting at or before it
// (`from` its value at start_ms).
struct OtherServo {
  double from = 0, to = 0;
  double tolerance = 1;
  std::vector<compiler::Segment> curve;
};

struct TipLineRequest {
  compiler::ArmGeometry arm;
  Joints from{};          // where the joints are when the move starts
  Point to{};             // the line's end, mm
  double pitch_from = 0;  // degrees; the line starts at the tip of `from`
  double pitch_to = 0;
  bool elbow_up = true;
  compiler::Easing ease;
  std::uint32_t start_ms = 0, end_ms = 0;  // absolute, whole milliseconds
  double tolerance_mm = 1;
  std::uint32_t min_action_ms = 20, max_action_ms = 30000;
  compiler::ControllerModel model = compiler::ControllerModel::StraightLine;
  std::array<int, 4> min{}, max{};  // each joint servo's limits
  std::vector<OtherServo> others;
  // Boundaries the actions must have, ascending, each strictly inside (start_ms, end_ms) and at
  // least min_action_ms from the next, from the start and from the end.
  std::vector<std::uint32_t> forced_ms;
  std::optional<Joints> end_joints;  // the joints' targets at the end, when already chosen
};

struct TipLineAction {
  std::uint32_t end_ms = 0;  // the action runs from the previous one's end (or start_ms)
  Joints targets{};
  std::vector<int> others;  // the other servos' targets, in the request's order
};

// Why a line cannot be followed, and where: `fraction` is how far along the line (the eased
// fraction of the distance, 0 at the start, 1 at the end), `point` the line's point there.
struct TipLineProblem {
  enum class Kind {
    BelowTable,  // point[2] < 0
    OutOfReach,  // needed/reach as in ArmSolution
    JointLimit,  // joint `joint` would be at `units`, `over` beyond its limit
    Rounding,    // at the end no whole-unit joints come within the tolerance: `error` mm
    Tolerance,   // no actions follow the line within the tolerance; `suggest` mm would do
  };
  Kind kind = Kind::Tolerance;
  double fraction = 0;
  Point point{};
  double pitch = 0;
  double needed = 0, reach = 0;
  std::size_t joint = 0;
  long long units = 0, over = 0;
  double angle = 0;  // the joint's angle there, degrees
  double error = 0, suggest = 0;
};

struct TipLineResult {
  std::vector<TipLineAction> actions;  // empty when `problem`
  std::optional<TipLineProblem> problem;
  Point from{};             // the line's start: the tip of `from`
  double max_error_mm = 0;  // over every millisecond of the actions
  std::uint32_t max_error_at_ms = 0;
};

TipLineResult fit_tip_line(const TipLineRequest& request);

// The tip's largest distance (mm) from the line of `request` at any millisecond of it, and
// where (ms, as the line's times), when the controller moves the joints as the fitted
// `actions` say: each named joint (`joints`, servo indices of base, shoulder, elbow and wrist)
// in a straight line from its previous target to the action's, under request.model.
// `board_per_ms`: the actions' milliseconds per millisecond of the line's (1 + the clock's
// error when the timeline was stretched for it).
struct TipLineError {
  double mm = 0;
  std::uint32_t at_ms = 0;
};
TipLineError measure_tip_line(const TipLineRequest& request,
                              const std::array<std::size_t, 4>& joints,
                              const std::vector<compiler::FittedAction>& actions,
                              double board_per_ms = 1);

}  // namespace seqc::compiler
