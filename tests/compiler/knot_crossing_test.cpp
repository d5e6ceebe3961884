// A keyframe is a point of the curve like any other: an action may run across a knot where
// every servo whose knot it is goes on moving and stays within its tolerance; holds, marked
// instants and knots whose crossing would miss stay action boundaries. Counts and boundaries are
// worked out by hand below; the motion is rebuilt from the actions alone (fitting_check.hpp) and
// compared at every millisecond with the straight pieces written here.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "compiler/fitting/fitter.hpp"
#include "tests/compiler/fitting_check.hpp"

namespace seqc::compiler {
namespace {

using fitting_check::Motion;
using fitting_check::segment;

// One servo's intended position, straight pieces (t0, t1, from, to) as the test writes them.
struct Line {
  double t0, t1, from, to;
};
double intended(const std::vector<Line>& lines, double t) {
  for (const Line& l : lines) {
    if (t <= l.t1) return l.from + (l.to - l.from) * (t - l.t0) / (l.t1 - l.t0);
  }
  return lines.back().to;
}

Timeline timeline_of(const std::vector<std::vector<Line>>& servos, double tol, int end) {
  Timeline tl;
  tl.resize(servos.size());
  const Easing none{};
  for (std::size_t s = 0; s < servos.size(); ++s) {
    for (const Line& l : servos[s]) {
      tl.add(s, segment(static_cast<int>(l.t0), static_cast<int>(l.t1), l.from, l.to,
                        l.from == l.to ? CurveKind::Hold : CurveKind::Linear, none, tol));
    }
  }
  tl.end = ExactMs(end);
  return tl;
}

// The largest distance, at every millisecond, between the motion rebuilt from the actions and
// the pieces, over every servo.
double worst(const FitResult& fit, const std::vector<std::vector<Line>>& servos, int end) {
  double most = 0;
  for (std::size_t s = 0; s < servos.size(); ++s) {
    const Motion m(fit.actions, std::round(servos[s].front().from), s);
    for (int t = 0; t <= end; ++t)
      most = std::max(most, std::abs(m.at(t) - intended(servos[s], t)));
  }
  return most;
}

// Knots 50 ms apart, each inside a servo's move: A bends a little at 600 ms (100 to 200, then
// 200 to 302), B at 650 ms (500 to 565, then on at the same speed to 620). With every knot a
// boundary that is three actions (0-600, 600-650, 650-1200); one straight action from 0 to
// 1200 ms is A's line 100 -> 302, 1 unit from 200 at 600 ms (its farthest), and B's line
// 500 -> 620, exactly 565 at 650 ms: within tolerance 2, so one action.
TEST(KnotCrossing, OneActionRunsAcrossTwoServosKnotsAFewMsApart) {
  const std::vector<std::vector<Line>> servos = {{{0, 600, 100, 200}, {600, 1200, 200, 302}},
                                                 {{0, 650, 500, 565}, {650, 1200, 565, 620}}};
  const FitResult fit = fit_timeline(timeline_of(servos, 2, 1200));
  ASSERT_EQ(fit.actions.size(), 1u);
  EXPECT_EQ(fit.actions[0].start_ms, 0u);
  EXPECT_EQ(fit.actions[0].time_ms, 1200u);
  EXPECT_TRUE(fit.shortfalls.empty());
  const double err = worst(fit, servos, 1200);
  EXPECT_NEAR(err, 1.0, 1e-9);  // A at 600 ms
  EXPECT_LE(fit.max_error, 2.0);
}

// A hold stays a boundary: A rises 100 to 200 over 1 s, holds 20 ms, rises to 300 over 1 s. One
// line 100 -> 300 over 2,020 ms would stay within 0.99 of it (199.01 at 1,000 ms, 200.99 at
// 1,020), inside tolerance 2, but a servo at rest is an exact boundary: three actions, at 0,
// 1,000 and 1,020 ms, and B (a straight line throughout) is cut there with them.
TEST(KnotCrossing, AHoldStaysAnExactBoundary) {
  const std::vector<std::vector<Line>> servos = {
      {{0, 1000, 100, 200}, {1000, 1020, 200, 200}, {1020, 2020, 200, 300}}, {{0, 2020, 500, 700}}};
  const FitResult fit = fit_timeline(timeline_of(servos, 2, 2020));
  ASSERT_EQ(fit.actions.size(), 3u);
  EXPECT_EQ(fit.actions[1].start_ms, 1000u);
  EXPECT_EQ(fit.actions[2].start_ms, 1020u);
  EXPECT_LE(worst(fit, servos, 2020), 2.0);
}

// A turn cannot be crossed: A goes 100 to 200 over 500 ms and back to 100. An action across
// 500 ms would have to pass within 2 of 200 there and of the curve 20 ms either side (196 at
// 480 and 520), so crossing saves nothing over two actions ending at the turn: the knot stays
// the boundary, A's target there 200.
TEST(KnotCrossing, AKnotWhoseCrossingWouldMissStaysABoundary) {
  const std::vector<std::vector<Line>> servos = {{{0, 500, 100, 200}, {500, 1000, 200, 100}}};
  const FitResult fit = fit_timeline(timeline_of(servos, 2, 1000));
  ASSERT_EQ(fit.actions.size(), 2u);
  EXPECT_EQ(fit.actions[0].time_ms, 500u);
  ASSERT_EQ(fit.actions[0].targets.size(), 1u);
  EXPECT_EQ(fit.actions[0].targets[0].position, 200);
  EXPECT_LE(worst(fit, servos, 1000), 2.0);
}

// A marked instant (an `at:` cue, a section, a tempo change) stays a boundary: the first case
// with a marker at 600 ms is two actions, 0-600 and 600-1200 (B's knot at 650 still crossed:
// its line 560 -> 620 is 565 at 650 ms, A is one straight piece).
TEST(KnotCrossing, AMarkedInstantStaysABoundary) {
  const std::vector<std::vector<Line>> servos = {{{0, 600, 100, 200}, {600, 1200, 200, 302}},
                                                 {{0, 650, 500, 565}, {650, 1200, 565, 620}}};
  Timeline tl = timeline_of(servos, 2, 1200);
  tl.markers.push_back({ExactMs(600), "at 600ms", {}});
  const FitResult fit = fit_timeline(tl);
  ASSERT_EQ(fit.actions.size(), 2u);
  EXPECT_EQ(fit.actions[1].start_ms, 600u);
  EXPECT_EQ(fit.actions[1].time_ms, 600u);
  EXPECT_LE(worst(fit, servos, 1200), 2.0);
}

}  // namespace
}  // namespace seqc::compiler
