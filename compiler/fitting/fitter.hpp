// Fitting: the whole timeline into controller actions. An action lasts min_action_ms to
// max_action_ms (whole milliseconds); each servo it names moves from where it is to its target
// over the action's time, and servos it omits hold. How it moves is the controller model
// (ControllerModel): a straight line between whole-unit targets, or that line rounded or
// truncated to whole units at every instant. Every tolerance promised below is checked against
// that model, at every millisecond.
//
// Boundaries are whole milliseconds on the absolute timeline, so rounding never accumulates:
// every segment boundary of every servo becomes one (a knot), merged when two fall closer than
// the shortest action. A knot inside a move (every servo whose knot it is moves on both sides,
// from one segment straight into the next, none of them a first move from an unknown position
// nor a `steps:`/`path: line` piece, and no marker within the shortest action of it) is a point
// of the curve like any other: a run of such knots, within kFineMs and crossable by some action
// of twice the shortest length within tolerance, is fitted as one stretch whose actions may run
// across them, and that fit is kept only where it has fewer actions and no more shortfalls than
// the fit below, which ends actions at every knot. There a knot is an action boundary for every
// servo; the servos whose own segments meet there have their targets pinned to the intended
// position rounded to a whole unit. Between knots where every moving servo follows a straight line,
// one action (or equal parts of at most max_action_ms) is exact. Where curves run, a stretch (over
// the knots where the same servos stay curved and one of them is mid-curve) is fitted with all its
// curved servos sharing the actions' boundaries, and the fewest actions are searched for twice:
// once with every target on the rounded curve (the on-curve fit), once with each target not pinned
// free to be any whole unit within the tolerance of the curve there and within the servo's limits
// (the free fit: a dynamic program over boundaries that carries, per boundary, the set of end
// values each servo can reach; exact for one servo, a small beam of labels for several, on a
// coarser grid of boundaries where the search would cost more than about the on-curve fit's time).
// The one with fewer actions is kept, the on-curve one on a tie; where a search stops at a
// shortfall, the whole stretch is fitted on the curve too and the better kept: one no worse in both
// actions and worst miss, else (one saves actions, the other misses by less) the one with fewer
// shortfalls, then fewer actions. The free fit never costs an action except to miss by less where
// even the shortest actions miss (more misses of no larger size are not worth one), and never
// misses where the on-curve fit does not. No stretch begins with an action that moves no servo
// unless every fit with the fewest actions needs one. A stretch too long to search in one piece is
// cut where its servos move least (or at a knot), the cut pinned like a knot, and each part
// searched alone.
//
// A stretch longer than 10 s (fitting/stretch.hpp, kFineMs) is fitted knot interval by knot
// interval, each searched on a bounded number of evenly spaced instants with its tolerance
// narrowed by a margin for what lies between them and for rounding its boundaries to whole
// milliseconds, so that its cost follows its actions rather than its milliseconds: its
// boundaries fall on those instants, it is still within tolerance at every millisecond, and its
// errors and shortfalls are measured at two instants per sample of each action, at most 65.
//
// Where even the shortest action cannot meet a tolerance, the result says where and by how
// much (a shortfall), and the fit goes on with shortest actions.
//
// An action names every servo that has a segment during it (a move or a `wait` hold); an
// action during which none has is a hold naming every servo whose position is known.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "base/source.hpp"
#include "compiler/program/controller_model.hpp"
#include "compiler/timeline/timeline.hpp"

namespace seqc::compiler {

struct ServoLimits {
  int min = -1'000'000;
  int max = 1'000'000;
};

struct FitOptions {
  std::uint32_t min_action_ms = 20;
  std::uint32_t max_action_ms = 30000;
  ControllerModel model = ControllerModel::StraightLine;
  // Whether targets between knots may lie anywhere within the tolerance (the free fit); false
  // keeps only the on-curve fit.
  bool free_end_points = true;
  // Per servo (output index): no target leaves these. Servos past the end are unlimited.
  std::vector<ServoLimits> limits;
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
  // The largest distance between the controller's motion (under the model) and the intended
  // curve, at whole milliseconds, over every named servo (straight moves: rounding only).
  double max_error = 0;
  std::uint32_t max_error_at_ms = 0;
  std::size_t max_error_servo = 0;
  std::vector<FitShortfall> shortfalls;
};

FitResult fit_timeline(const Timeline& timeline, const FitOptions& options = {});

// The timeline fitted for a board whose clock runs `clock_ppm` parts per million fast (slow when
// negative): a board millisecond lasts 1 / (1 + e) host ms, so the author's instants are
// stretched by (1 + e) before the fit rounds each boundary once, and the error never accumulates
// action by action. 0 is fit_timeline() itself.
FitResult fit_timeline_on_board(const Timeline& timeline, const FitOptions& options,
                                std::int32_t clock_ppm);

}  // namespace seqc::compiler
