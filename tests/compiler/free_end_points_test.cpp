// Free end points, checked from the outside as in fitting_test.cpp (fitting_check.hpp): a
// hand-worked curve, the exact fewest actions on one curve, servos moving together within
// tolerance, never more actions than the on-curve fit (below half a unit of tolerance too) and
// an on-curve fit where free end points save nothing, a miss only where the on-curve fit misses
// as much, targets inside the servos' limits, and no leading still action.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "compiler/fitting/fitter.hpp"
#include "compiler/timeline/easing.hpp"
#include "tests/bench/fit_reference.hpp"
#include "tests/compiler/easing_reference.hpp"
#include "tests/compiler/fitting_check.hpp"
#include "tests/compiler/lang_test_util.hpp"

namespace seqc::compiler {
namespace {

using namespace fitting_check;

TEST(Fitting, FreeEndPointsSaveAnActionOnAHandWorkedCurve) {
  const Timeline tl = eased_move(0, 18, 60, *parse_easing("quad-in").easing, 1);
  const FitResult free = fit_timeline(tl);
  ASSERT_EQ(free.actions.size(), 2u);
  EXPECT_TRUE(free.shortfalls.empty());
  // Whatever the two targets are, the motion stays within 1 of t^2 / 200 at every millisecond.
  const Motion motion(free.actions, 0);
  for (int t = 0; t <= 60; ++t) {
    EXPECT_LE(std::abs(motion.at(t) - t * t / 200.0), 1 + 1e-9) << t;
  }
  FitOptions on_curve;
  on_curve.free_end_points = false;
  EXPECT_EQ(fit_timeline(tl, on_curve).actions.size(), 3u);
}

// The same curve compiled from a file: CompileOptions::free_end_points chooses between the two
// fits (fit_bench compares them on the examples this way).
TEST(Fitting, CompileOptionsChooseTheFreeOrTheOnCurveFit) {
  testing::MemoryFiles files;
  files.files["main.yaml"] =
      "robot: xarm\nsequence:\n  - move: {base: 0}\n    time: 1s\n  - move: {base: 18}\n"
      "    time: 60ms\n    ease: quad-in\n";
  CompileOptions options;
  const CompileOutput free = compile_file("main.yaml", files, options);
  options.free_end_points = false;
  const CompileOutput on_curve = compile_file("main.yaml", files, options);
  // The first move, then the curve's two actions (free) or three (on the curve).
  EXPECT_EQ(testing::program_of(free).keyframes.size(), 3u);
  EXPECT_EQ(testing::program_of(on_curve).keyframes.size(), 4u);
}

// One curve's free fit has exactly the fewest actions any fit with free end points can have:
// the count of an exhaustive search over every (millisecond, whole unit) state written apart
// from the fitter (fit_reference.hpp, the benchmark's reference), on eased moves of 250 and
// 600 ms, short and long, at tolerance 1 and 2.
TEST(Fitting, OneCurvesFreeFitHasTheExactFewestActions) {
  const std::vector<std::string> names = {
      "sine-in-out", "quad-in",  "cubic-out",   "quart-in-out",
      "expo-in-out", "circ-out", "back-in-out", "cubic-bezier(0.2, 0.8, 0.6, 0.1)"};
  int compared = 0;
  for (const std::string& name : names) {
    for (const int ms : {250, 600}) {
      for (const auto& [move, tol] : {std::pair{60.0, 1.0}, std::pair{300.0, 2.0}}) {
        fit_reference::Piece piece;
        piece.t0 = 0;
        piece.t1 = ms;
        piece.from = 400;
        piece.to = 400 + move;
        piece.easing = *parse_easing(name).easing;
        const int minimum = fit_reference::free_minimum(piece, ms, tol);
        if (minimum >= (1 << 30)) continue;  // even 20 ms actions cannot follow it
        const FitResult fit = fit_timeline(eased_move(piece.from, piece.to, ms, piece.easing, tol));
        EXPECT_TRUE(fit.shortfalls.empty()) << name << " " << ms << " ms";
        EXPECT_EQ(static_cast<int>(fit.actions.size()), minimum)
            << name << " over " << ms << " ms by " << move << " at tolerance " << tol;
        ++compared;
      }
    }
  }
  EXPECT_GE(compared, 20);  // of the 32, those 20 ms actions can follow
}

// Servos moving together (each its own eased moves, their boundaries apart) are fitted within
// tolerance at every millisecond: each servo's motion is rebuilt from the actions (a straight
// line to each target it is sent, a hold otherwise) and compared with the curves computed from
// the textbook formulas. The moves are gentle enough for 20 ms actions and their boundaries lie
// on a 100 ms grid (so no two servos' boundaries are merged into one), so no shortfall is
// excused.
TEST(Fitting, ServosMovingTogetherStayWithinToleranceAtEveryMillisecond) {
  struct Piece {
    double t0, t1, from, to;
    Easing easing;
  };
  std::mt19937 rng(20261128);
  std::uniform_real_distribution<double> unit(0, 1);
  const std::vector<std::string> names = {"sine-in-out", "quad-in-out", "cubic-in-out",
                                          "sine-out",    "quad-in",     "cubic-out"};
  for (int round = 0; round < 12; ++round) {
    const std::size_t servos = 2 + static_cast<std::size_t>(round % 3) * 2;  // 2, 4, 6
    const double tol = round % 2 == 0 ? 1 : 2;
    Timeline tl;
    tl.resize(servos);
    std::vector<std::vector<Piece>> tracks(servos);
    const double end = 2000;
    for (std::size_t s = 0; s < servos; ++s) {
      double t = 0, pos = 300 + std::floor(unit(rng) * 400);
      while (t < end) {
        double len = 100 * std::floor(3 + unit(rng) * 8);
        if (end - (t + len) < 300) len = end - t;  // no piece shorter than 300 ms
        Piece p{t, t + len, pos, pos + std::floor((unit(rng) - 0.5) * 300),
                *parse_easing(names[static_cast<std::size_t>(unit(rng) * 6) % 6]).easing};
        Segment seg;
        seg.start = ExactMs(static_cast<std::int64_t>(p.t0));
        seg.end = ExactMs(static_cast<std::int64_t>(p.t1));
        seg.from = p.from;
        seg.to = p.to;
        seg.kind = CurveKind::Eased;
        seg.easing = p.easing;
        seg.tolerance = tol;
        tl.add(s, seg);
        tracks[s].push_back(p);
        pos = p.to;
        t = p.t1;
      }
    }
    tl.end = ExactMs(static_cast<std::int64_t>(end));
    const FitResult fit = fit_timeline(tl);
    EXPECT_TRUE(fit.shortfalls.empty()) << "round " << round;
    for (std::size_t s = 0; s < servos; ++s) {
      const Motion motion(fit.actions, std::round(tracks[s].front().from), s);
      double worst = 0;
      int worst_at = 0;
      for (int t = 0; t <= static_cast<int>(end); ++t) {
        const auto p = std::find_if(tracks[s].begin(), tracks[s].end(),
                                    [&](const Piece& x) { return t <= x.t1; });
        const double u = (t - p->t0) / (p->t1 - p->t0);
        const double want = p->from + (p->to - p->from) * testing::ease_ref::at(p->easing, u);
        if (std::abs(motion.at(t) - want) > worst) {
          worst = std::abs(motion.at(t) - want);
          worst_at = t;
        }
      }
      EXPECT_LE(worst, tol + 1e-9)
          << "round " << round << ", servo " << s << ", at " << worst_at << " ms";
    }
  }
}

// Random single curves and servos moving together: the fit never has more actions than the
// on-curve fit alone (it keeps the better of the two).
TEST(Fitting, NeverMoreActionsThanTheOnCurveFit) {
  std::mt19937 rng(20261125);
  std::uniform_real_distribution<double> unit(0, 1);
  const std::vector<std::string> names = {"sine-in-out", "cubic-in",    "quad-out",
                                          "back-in-out", "expo-in-out", "circ-in",
                                          "bounce-out",  "elastic-out", "quart-in-out"};
  FitOptions on_curve;
  on_curve.free_end_points = false;
  int fewer = 0;
  for (int round = 0; round < 60; ++round) {
    const std::size_t servos = 1 + static_cast<std::size_t>(round % 8);
    Timeline tl;
    tl.resize(servos);
    double end = 0;
    for (std::size_t s = 0; s < servos; ++s) {
      double t = 0, pos = 300 + std::floor(unit(rng) * 400);
      while (t < 1500) {
        const double len = std::floor(150 + unit(rng) * 650);
        Segment seg;
        seg.start = ExactMs(static_cast<std::int64_t>(t));
        seg.end = ExactMs(static_cast<std::int64_t>(t + len));
        seg.from = pos;
        seg.to = pos + std::floor((unit(rng) - 0.5) * 600);
        seg.kind = CurveKind::Eased;
        seg.easing = *parse_easing(names[static_cast<std::size_t>(unit(rng) * 9) % 9]).easing;
        seg.tolerance = round % 2 == 0 ? 1 : 2;
        tl.add(s, seg);
        pos = seg.to;
        t += len;
      }
      end = std::max(end, t);
    }
    tl.end = ExactMs(static_cast<std::int64_t>(end));
    const std::size_t fitted = fit_timeline(tl).actions.size();
    const std::size_t before = fit_timeline(tl, on_curve).actions.size();
    EXPECT_LE(fitted, before) << "round " << round << ", " << servos << " servos";
    fewer += fitted < before ? 1 : 0;
  }
  EXPECT_GT(fewer, 30);  // and the free end points do save actions
}

// Where even the shortest actions miss (an elastic's first swings, a bounce), both fits report
// shortfalls. The fit kept spends an action more than the on-curve fit only to miss by less:
// more misses of the same size are not worth an action.
// Elastic-out over 500 ms from 50 to 450 at tolerance 1 is such a curve: its first swing turns
// round within 20 ms, so both fits miss there by the same worst amount, whatever comes after.
TEST(Fitting, AnActionMoreThanTheOnCurveFitOnlyForASmallerWorstMiss) {
  FitOptions on_curve;
  on_curve.free_end_points = false;
  auto worst_miss = [](const FitResult& r) {
    double most = 0;
    for (const FitShortfall& f : r.shortfalls) most = std::max(most, f.error);
    return most;
  };
  int both_miss = 0;
  for (const char* name : {"elastic-out", "elastic-in", "bounce-out", "bounce-in-out"}) {
    for (int ms : {300, 500, 800}) {
      for (double tol : {1.0, 2.0}) {
        const Timeline tl = eased_move(50, 450, ms, *parse_easing(name).easing, tol);
        const FitResult fitted = fit_timeline(tl);
        const FitResult before = fit_timeline(tl, on_curve);
        SCOPED_TRACE(std::string(name) + " over " + std::to_string(ms) + " ms at tolerance " +
                     std::to_string(tol));
        if (fitted.actions.size() > before.actions.size()) {
          EXPECT_LT(worst_miss(fitted), worst_miss(before) - 1e-6);
        }
        both_miss += !fitted.shortfalls.empty() && !before.shortfalls.empty() ? 1 : 0;
      }
    }
  }
  EXPECT_GT(both_miss, 6);  // the cases are the ones where both fits miss
}

// A free end point never leaves the servo's limits. Curves that dip to just above the bottom of
// the servo's range (0 here) and come back: Hermite pieces from 40 to 40 whose inner control
// points sit at p1 = p2 = (m - 10) / 0.75, so that the middle, 40/8 + 3/4 p1 + 40/8, is m (0.2
// or 0.5). Lines across a dip fit best with their ends below the curve, where the band of whole
// units within tolerance reaches below 0; the fit keeps at 0 or above.
TEST(Fitting, FreeEndPointsStayWithinTheServosLimits) {
  FitOptions limited;
  limited.limits = {{0, 1000}};
  int below_without_limits = 0;
  for (int ms : {300, 600, 900, 1200, 1500}) {
    for (double m : {0.2, 0.5}) {
      const double p1 = (m - 10) / 0.75, h = ms;
      Segment seg;
      seg.start = ExactMs(0);
      seg.end = ExactMs(ms);
      seg.from = seg.to = 40;
      seg.kind = CurveKind::Hermite;
      seg.slope_from = static_cast<float>(-(40 - p1) * 3 / h);
      seg.slope_to = -seg.slope_from;
      seg.tolerance = 2;
      Timeline tl;
      tl.resize(1);
      tl.add(0, seg);
      tl.end = ExactMs(ms);
      for (const FittedAction& a : fit_timeline(tl).actions) {
        below_without_limits += a.targets[0].position < 0 ? 1 : 0;
      }
      const FitResult fit = fit_timeline(tl, limited);
      for (const FittedAction& a : fit.actions) {
        EXPECT_GE(a.targets[0].position, 0) << ms << " ms, " << m << ", at " << a.start_ms;
      }
      // Still within tolerance at every millisecond.
      EXPECT_TRUE(fit.shortfalls.empty());
      const Motion motion(fit.actions, 40);
      Intended want;
      want.t1 = h;
      want.from = want.to = 40;
      want.hermite = true;
      want.slope_from = seg.slope_from;
      want.slope_to = seg.slope_to;
      want.tolerance = 2;
      for (int t = 0; t <= ms; ++t) {
        EXPECT_LE(std::abs(motion.at(t) - want.at(t)), 2 + 1e-6) << ms << " ms, " << m << ", " << t;
      }
    }
  }
  // Without limits the fit does use the units below 0, so the limits above were in play.
  EXPECT_GT(below_without_limits, 0);
}

// An eased move whose curve barely leaves its start does not begin with an action that moves
// nothing: cubic-in from 500 to 600 over 1 s stays within 1 of 500 for its first 215 ms
// (100 x 0.215^3 = 0.99), so a first action holding 500 fits, but one that moves does too.
TEST(Fitting, AnEasedMoveDoesNotBeginWithAnActionThatMovesNothing) {
  for (const char* ease : {"cubic-in", "expo-in", "quint-in"}) {
    auto out = testing::compile_text(
        std::string("robot: xarm\nsequence:\n") + "  - move: {base: 500}\n    time: 1s\n" +
        "  - move: {base: 600}\n    time: 1s\n    ease: " + ease + "\n");
    const ServoProgram& p = testing::program_of(out);
    ASSERT_GE(p.keyframes.size(), 3u) << ease;
    EXPECT_EQ(p.keyframes[0].targets, (std::vector<lsc::ServoTarget>{{6, 500}})) << ease;
    ASSERT_EQ(p.keyframes[1].targets.size(), 1u) << ease;
    EXPECT_NE(p.keyframes[1].targets[0].position, 500) << ease;
  }
}

// Where free end points save no action, the fit is one with every target on the rounded curve:
// each target is the curve at the action's end, from the textbook formula, rounded. Eased
// moves of 250 to 900 ms, short and long, at tolerance 1 and 2; the cases compared are those
// where the on-curve fit needs as many actions as the free one.
TEST(Fitting, WhereFreeEndPointsSaveNothingEveryTargetIsOnTheRoundedCurve) {
  FitOptions on_curve;
  on_curve.free_end_points = false;
  const std::vector<std::string> names = {"sine-in-out", "quad-in",     "cubic-out", "quart-in-out",
                                          "circ-out",    "back-in-out", "linear",    "expo-in-out"};
  int ties = 0;
  for (const std::string& name : names) {
    const Easing easing = *parse_easing(name).easing;
    for (const int ms : {250, 400, 600, 900}) {
      for (const auto& [move, tol] : {std::pair{30.0, 1.0}, std::pair{60.0, 1.0},
                                      std::pair{120.0, 2.0}, std::pair{300.0, 2.0}}) {
        const Timeline tl = eased_move(400, 400 + move, ms, easing, tol);
        const FitResult free = fit_timeline(tl);
        const FitResult before = fit_timeline(tl, on_curve);
        if (!free.shortfalls.empty() || free.actions.size() != before.actions.size()) continue;
        ++ties;
        for (const FittedAction& a : free.actions) {
          const double end = a.start_ms + a.time_ms;
          const double curve = 400 + move * testing::ease_ref::at(easing, end / ms);
          ASSERT_EQ(a.targets.size(), 1u);
          EXPECT_EQ(a.targets[0].position, std::lround(curve))
              << name << " over " << ms << " ms by " << move << " at tolerance " << tol
              << ", the action ending at " << end << " ms";
        }
      }
    }
  }
  EXPECT_GE(ties, 20);  // of the 128
}

// Below half a unit of tolerance the rounded curve is not always a free target (10.4 rounds to
// 10, more than 0.3 from it), so the on-curve fit is not one of the free fits there; the fit
// kept still never needs more actions than the on-curve one, nor misses more often.
TEST(Fitting, BelowHalfAUnitTheFitNeverNeedsMoreActionsThanOnTheCurve) {
  FitOptions on_curve;
  on_curve.free_end_points = false;
  int compared = 0;
  for (const char* name : {"sine-in-out", "quad-in", "cubic-out", "linear", "circ-in"}) {
    for (const int ms : {200, 500, 800}) {
      for (const double tol : {0.3, 0.45}) {
        const Timeline tl = eased_move(400, 437, ms, *parse_easing(name).easing, tol);
        const FitResult free = fit_timeline(tl);
        const FitResult before = fit_timeline(tl, on_curve);
        EXPECT_LE(std::make_pair(free.shortfalls.size(), free.actions.size()),
                  std::make_pair(before.shortfalls.size(), before.actions.size()))
            << name << " over " << ms << " ms at tolerance " << tol;
        ++compared;
      }
    }
  }
  EXPECT_EQ(compared, 30);
}

}  // namespace
}  // namespace seqc::compiler
