// Fitting, checked from the outside: the controller's motion is rebuilt here from the actions
// alone (each named servo in a straight line to its target, others holding) and sampled every
// quarter millisecond against the intended curve (the tolerance is a promise at every
// millisecond), independently of the fitter's own
// bookkeeping. Random curves of every easing family, bezier and Hermite, 0.5-5 s, small and
// full-range.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "compiler/fitting/fitter.hpp"
#include "compiler/timeline/easing.hpp"
#include "tests/compiler/lang_test_util.hpp"

namespace seqc::compiler {
namespace {

// The controller's position of servo 0 at time t, from the actions alone.
double controller_at(const std::vector<FittedAction>& actions, double start_value, double t) {
  double pos = start_value;
  for (const FittedAction& a : actions) {
    const FittedTarget* mine = nullptr;
    for (const FittedTarget& x : a.targets) {
      if (x.servo == 0) mine = &x;
    }
    const double s = a.start_ms, e = a.start_ms + a.time_ms;
    if (mine == nullptr) {
      if (t <= e) return pos;
      continue;
    }
    if (t <= e) return t <= s ? pos : pos + (mine->position - pos) * (t - s) / (e - s);
    pos = mine->position;
  }
  return pos;
}

Timeline one_curve(const Segment& seg) {
  Timeline tl;
  tl.resize(1);
  Segment start;  // where the servo is before the curve: a short hold
  start.kind = CurveKind::Hold;
  start.start = ExactMs(0);
  start.end = seg.start;
  start.from = start.to = seg.from;
  tl.add(0, start);
  tl.add(0, seg);
  tl.end = ExactMs(static_cast<std::int64_t>(seg.end.round()));
  return tl;
}

TEST(Fitting, RandomCurvesStayWithinToleranceAndBeatUniformSampling) {
  std::mt19937 rng(20261123);
  std::uniform_real_distribution<double> unit(0, 1);
  std::vector<std::string> names = easing_names();
  names.push_back("cubic-bezier(0.42, 0, 0.58, 1)");
  names.push_back("cubic-bezier(0.1, 0.9, 0.2, 1)");
  names.push_back("hermite");
  int curves = 0;
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
      if (name == "hermite") {
        seg.kind = CurveKind::Hermite;
        seg.slope_from = 0;
        seg.slope_to = (seg.to - seg.from) / static_cast<double>(ms) * unit(rng) * 2;
      } else {
        seg.kind = CurveKind::Eased;
        seg.easing = *parse_easing(name).easing;
      }
      const FitResult fit = fit_timeline(one_curve(seg));
      // The contract holds at every millisecond; between them a curve with a cusp (bounce)
      // can stray by what it moves in a fraction of a millisecond, allowed for separately.
      double worst = 0, worst_between = 0;
      for (double t = 100; t <= static_cast<double>(100 + ms); t += 0.25) {
        const double err = std::abs(controller_at(fit.actions, seg.from, t) - seg.value(t));
        (t == std::floor(t) ? worst : worst_between) =
            std::max(t == std::floor(t) ? worst : worst_between, err);
      }
      // A shortfall is allowed only where 20 ms actions cannot follow (bounce, elastic at a
      // tight tolerance): then it is reported, never silent.
      if (fit.shortfalls.empty()) {
        EXPECT_LE(worst, seg.tolerance + 1e-6) << name << " over " << ms << " ms";
        EXPECT_LE(worst_between, seg.tolerance + 0.25) << name << " over " << ms << " ms";
      }
      for (const FittedAction& a : fit.actions) {
        EXPECT_GE(a.time_ms, 20u) << name;
        EXPECT_LE(a.time_ms, 30000u) << name;
      }
      // Never more than sampling the curve every 20 ms (plus the hold before it).
      EXPECT_LE(fit.actions.size(), 1 + static_cast<std::size_t>(ms / 20)) << name;
      ++curves;
    }
  }
  EXPECT_EQ(curves, 4 * static_cast<int>(names.size()));
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

}  // namespace
}  // namespace seqc::compiler
