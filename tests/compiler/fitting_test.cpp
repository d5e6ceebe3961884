// Fitting, checked from the outside. The controller's motion is rebuilt here from the actions
// alone (each named servo in a straight line to its target, others holding) and compared with
// the intended curve computed here from the textbook formulas (easing_reference.hpp; Hermite
// pieces in Bezier form), never through the timeline's or the easing code's own evaluation:
// within tolerance at every millisecond, and within what a cusp moves in a quarter millisecond
// between them. Random curves of every easing family, bezier and Hermite, 0.5-5 s, small and
// full-range.
//
// Where the fitter reports a shortfall, its action is exempt from the tolerance, and the
// shortfall itself is proven here: a search over every motion the controller could make
// around that instant (breakpoints on the millisecond grid, at least 20 ms apart, each at any
// whole unit within the tolerance of the intended position there, knots at the intended
// position rounded) finds none within tolerance.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>

#include "compiler/fitting/fitter.hpp"
#include "compiler/frontend/profiles.hpp"
#include "compiler/timeline/easing.hpp"
#include "tests/compiler/easing_reference.hpp"
#include "tests/compiler/fitting_check.hpp"
#include "tests/compiler/lang_test_util.hpp"

namespace seqc::compiler {
namespace {

using namespace fitting_check;

TEST(Fitting, RandomCurvesStayWithinToleranceAndBeatUniformSampling) {
  std::mt19937 rng(20261123);
  std::uniform_real_distribution<double> unit(0, 1);
  std::vector<std::string> names = easing_names();
  names.push_back("cubic-bezier(0.42, 0, 0.58, 1)");
  names.push_back("cubic-bezier(0.1, 0.9, 0.2, 1)");
  names.push_back("hermite");
  int curves = 0, with_shortfalls = 0;
  for (int round = 0; round < 4; ++round) {
    for (const std::string& name : names) {
      Segment seg;
      seg.start = ExactMs(100);
      const auto ms = static_cast<std::int64_t>(500 + unit(rng) * 4500);
      seg.end = ExactMs(100 + ms);
      const bool full = round % 2 == 0;
      seg.from = full ? 100 : 400 + std::floor(unit(rng) * 100);
      seg.to = full ? 900 : seg.from + 20 + std::floor(unit(rng) * 60);
      seg.tolerance = round < 2 ? 2 : 0.75;
      Intended want;
      want.t0 = 100;
      want.t1 = static_cast<double>(100 + ms);
      want.from = seg.from;
      want.to = seg.to;
      want.tolerance = seg.tolerance;
      if (name == "hermite") {
        seg.kind = CurveKind::Hermite;
        seg.slope_from = 0;
        // A float, as the timeline stores it, so that both sides see the same curve.
        seg.slope_to =
            static_cast<float>((seg.to - seg.from) / static_cast<double>(ms) * unit(rng) * 2);
        want.hermite = true;
        want.slope_from = seg.slope_from;
        want.slope_to = seg.slope_to;
      } else {
        seg.kind = CurveKind::Eased;
        seg.easing = *parse_easing(name).easing;
        want.easing = seg.easing;
      }
      const FitResult fit = fit_timeline(one_curve(seg));
      const Motion motion(fit.actions, seg.from);
      const std::int64_t end = 100 + ms;
      const std::string what =
          name + " over " + std::to_string(ms) + " ms, tolerance " + std::to_string(seg.tolerance);

      // Every shortfall is where it says, by what it says, and unavoidable.
      for (const FitShortfall& f : fit.shortfalls) {
        const double t = f.at_ms;
        const double err = std::abs(motion.at(t) - want.at(t));
        EXPECT_NEAR(err, f.error, 1e-6) << what << " at " << f.at_ms;
        EXPECT_GT(err, want.tolerance_at(f.at_ms)) << what << " at " << f.at_ms;
        EXPECT_TRUE(shortfall_proven(want, f.at_ms, end))
            << what << ": a motion within tolerance exists around " << f.at_ms << " ms";
      }
      with_shortfalls += fit.shortfalls.empty() ? 0 : 1;

      // Outside the actions holding a shortfall, the tolerance holds at every millisecond.
      // Between them a curve with a cusp (bounce) can stray by what it moves in a fraction of
      // a millisecond.
      for (const FittedAction& a : fit.actions) {
        const std::int64_t s = a.start_ms, e = s + a.time_ms;
        const bool excused =
            std::any_of(fit.shortfalls.begin(), fit.shortfalls.end(),
                        [&](const FitShortfall& f) { return f.at_ms >= s && f.at_ms <= e; });
        if (excused) {
          // Where even the shortest actions miss, the fit goes on with shortest actions (the
          // last one up to the curve's end, rather than leave less than 20 ms after it).
          EXPECT_TRUE(a.time_ms == 20 || (e == end && a.time_ms < 40))
              << what << ": " << a.time_ms << " ms from " << s;
          continue;
        }
        for (std::int64_t t = s; t <= e; ++t) {
          const double err =
              std::abs(motion.at(static_cast<double>(t)) - want.at(static_cast<double>(t)));
          EXPECT_LE(err, want.tolerance_at(t) + 1e-6) << what << " at " << t << " ms";
          for (double q : {0.25, 0.5, 0.75}) {
            const double at = static_cast<double>(t) + q;
            if (at > static_cast<double>(e)) break;
            const double between = std::abs(motion.at(at) - want.at(at));
            EXPECT_LE(between, want.tolerance_at(t) + 0.25) << what << " at " << at << " ms";
          }
        }
      }
      // The actions follow one another from 0 to the end, each 20 ms to 30 s long.
      std::uint32_t reached = 0;
      for (const FittedAction& a : fit.actions) {
        EXPECT_EQ(a.start_ms, reached) << what;
        EXPECT_GE(a.time_ms, 20u) << what;
        EXPECT_LE(a.time_ms, 30000u) << what;
        reached = a.start_ms + a.time_ms;
      }
      EXPECT_EQ(reached, static_cast<std::uint32_t>(end)) << what;
      // Never more than sampling the curve every 20 ms (plus the hold before it).
      EXPECT_LE(fit.actions.size(), 1 + static_cast<std::size_t>(ms / 20)) << name;
      ++curves;
    }
  }
  EXPECT_EQ(curves, 4 * static_cast<int>(names.size()));
  // The tight tolerances do leave shortfalls (bounce, elastic), so their proofs were exercised.
  EXPECT_GT(with_shortfalls, 0);
}

TEST(Fitting, BoundariesAreRoundedOnTheAbsoluteTimeline) {
  // 440 moves of one beat at 110 bpm: the last action ends at 240,000 ms, not 239,800.
  std::string text = "robot: xarm\ntempo: 110\nsequence:\n  - move: home\n    time: 1b\n";
  text += "  - repeat: 219\n    do:\n      - move: {base: 600}\n        time: 1b\n";
  text += "      - move: {base: 400}\n        time: 1b\n";
  text += "  - move: {base: 500}\n    time: 1b\n";
  auto out = testing::compile_text(text);
  const ServoProgram& p = testing::program_of(out);
  ASSERT_EQ(p.keyframes.size(), 440u);
  const Keyframe& last = p.keyframes.back();
  EXPECT_EQ(last.start_ms + last.time_ms, 240000u);
  // Each beat is 545 or 546 ms, so that none drifts by more than half a millisecond.
  for (std::size_t i = 0; i < p.keyframes.size(); ++i) {
    const double exact_start = static_cast<double>(i) * 60000.0 / 110.0;
    EXPECT_LE(std::abs(p.keyframes[i].start_ms - exact_start), 0.5) << i;
  }
}

TEST(Fitting, StraightMovesStayOneActionAndLongOnesSplitEqually) {
  auto out = testing::compile_text(
      "robot: xarm\nsequence:\n  - move: home\n    time: 1s\n"
      "  - move: {base: 900}\n    time: 45s\n");
  const ServoProgram& p = testing::program_of(out);
  ASSERT_EQ(p.keyframes.size(), 3u);
  EXPECT_EQ(p.keyframes[1].time_ms, 22500);
  EXPECT_EQ(p.keyframes[2].time_ms, 22500);
  EXPECT_EQ(p.keyframes[1].targets, (std::vector<lsc::ServoTarget>{{6, 700}}));
}

TEST(Fitting, AnImpossibleToleranceIsAWarningWithWhereAndHowMuch) {
  auto out = testing::compile_text(
      "robot: xarm\nsequence:\n  - move: {base: 0}\n    time: 1s\n"
      "  - move: {base: 500}\n    time: 600ms\n    ease: elastic-out\n    tolerance: 0.2\n");
  ASSERT_NE(out.servo_program(), nullptr) << testing::diagnostics_of(out);
  const std::string d = testing::diagnostics_of(out);
  EXPECT_NE(d.find("5:5: warning: even 20ms actions cannot keep 'base' within 0.2 of this curve"),
            std::string::npos)
      << d;
}

// c(t) = t^2 / 200 (quad-in from 0 to 18 over 60 ms), tolerance 1: free end points fit it in two
// actions, targets on the rounded curve need three.
//
// Free: 0 -> 4 over [0, 30] ms, then 4 -> 18 over [30, 60] ms. c(30) = 4.5, so 4 is within 1.
//   Line 1, y = 4t/30: y - c = 4t/30 - t^2/200 is 0 at t = 0, -0.5 at t = 30, and largest where
//   4/30 = t/100, t = 13.3: 0.889 - 0.889 / 2 = 0.444. Within 1.
//   Line 2, y = 4 + 14(t - 30)/30: y - c is -0.5 at t = 30, 0 at t = 60, largest where
//   14/30 = t/100, t = 46.7: 11.78 - 10.89 = 0.889. Within 1.
// On the curve: two actions need one boundary e in 20..40 (each at least 20 ms), target
// p = round(e^2/200). For e in 20..31 the second line at t = 45 (c = 10.125) is above 11.125:
// the least is e = 29, p = 4: 4 + 14 x 16/31 = 11.23. For e in 32..40 the first line at
// t = 15 (c = 1.125) is above 2.125: the least is e = 33, p = 5: 5 x 15/33 = 2.27. So two

}  // namespace
}  // namespace seqc::compiler
