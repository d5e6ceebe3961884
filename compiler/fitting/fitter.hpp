// Fitting: the whole timeline into controller actions. An action lasts min_action_ms to
// max_action_ms (whole milliseconds); each servo it names moves in a straight line from where
// it is to its target over the action's time, and servos it omits hold.
//
// Boundaries are whole milliseconds on the absolute timeline, so rounding never accumulates:
// every segment boundary of every servo becomes one (a knot), merged when two fall closer than
// the shortest action. Between knots where every moving servo follows a straight line, one
// action (or equal parts of at most max_action_ms) is exact. Where a curve runs, boundaries are
// chosen greedily, each action as long as every servo's straight line stays within its
// segment's tolerance of the intended curve at every millisecond, targets rounded to whole
// device units included. Where even the shortest action cannot meet a tolerance, the result
// says where and by how much (a shortfall), and the fit goes on with shortest actions.
//
// An action names every servo that has a segment during it (a move or a `wait` hold); an
// action during which none has is a hold naming every servo whose position is known.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "compiler/source/source.hpp"
#include "compiler/timeline/timeline.hpp"

namespace seqc::compiler {

struct FitOptions {
  std::uint32_t min_action_ms = 20;
  std::uint32_t max_action_ms = 30000;
};

struct FittedTarget {
  std::size_t servo = 0;  // output index
  int position = 0;
};

struct FittedAction {
  std::uint32_t start_ms = 0;
  std::uint32_t time_ms = 0;
  std::vector<FittedTarget> targets;  // ascending servo index
  Location source;                    // the step whose segment is newest during the action
};

// Where the shortest actions still miss a tolerance.
struct FitShortfall {
  std::size_t servo = 0;
  std::uint32_t at_ms = 0;  // the worst instant
  double error = 0;         // distance from the intended curve there, device units
  double tolerance = 0;
  Location where;
};

struct FitResult {
  std::vector<FittedAction> actions;
  // The largest distance between the controller's motion and the intended curve, at whole
  // milliseconds, over every named servo (straight moves: rounding only).
  double max_error = 0;
  std::uint32_t max_error_at_ms = 0;
  std::size_t max_error_servo = 0;
  std::vector<FitShortfall> shortfalls;
};

FitResult fit_timeline(const Timeline& timeline, const FitOptions& options = {});

}  // namespace seqc::compiler
