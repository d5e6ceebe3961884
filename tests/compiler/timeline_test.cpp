// The timeline stage: exact time, the easing formulas at points worked out by hand, and the
// curves segments describe.
#include <gtest/gtest.h>

#include <cmath>

#include "compiler/timeline/easing.hpp"
#include "compiler/timeline/exact_time.hpp"
#include "compiler/timeline/speed_within_tolerance.hpp"
#include "compiler/timeline/timeline.hpp"

namespace seqc::compiler {
namespace {

TEST(ExactMs, BeatsAddUpWithoutDrift) {
  // A beat at 110 bpm is 60000/110 = 6000/11 ms; 440 of them are exactly 240 s.
  const ExactMs beat = ExactMs(60000) / ExactMs::from_double(110);
  EXPECT_EQ(beat, ExactMs::ratio(6000, 11));
  ExactMs t;
  for (int i = 0; i < 440; ++i) t += beat;
  EXPECT_EQ(t, ExactMs(240000));
  EXPECT_EQ(t.round(), 240000);
  // Rounding each beat on its own would have drifted: 545 ms x 440 = 239.8 s.
  EXPECT_EQ(beat.round() * 440, 239800);
}

TEST(ExactMs, RoundsHalvesAwayFromZeroAndCompares) {
  EXPECT_EQ(ExactMs::ratio(3, 2).round(), 2);
  EXPECT_EQ(ExactMs::ratio(5, 4).round(), 1);
  EXPECT_EQ(ExactMs::ratio(-3, 2).round(), -2);
  EXPECT_LT(ExactMs::ratio(1, 3), ExactMs::ratio(1, 2));
  EXPECT_EQ(ExactMs::from_double(1.5) * ExactMs(1000), ExactMs(1500));
  EXPECT_EQ(ExactMs::from_double(0.1) * ExactMs(1000), ExactMs(100));
}

Easing ease(const char* name) {
  auto p = parse_easing(name);
  EXPECT_TRUE(p.easing.has_value()) << name;
  return p.easing.value_or(Easing{});
}

TEST(Easing, EveryNamedCurveRunsFromZeroToOne) {
  for (const std::string& name : easing_names()) {
    const Easing e = ease(name.c_str());
    EXPECT_EQ(e.at(0), 0) << name;
    EXPECT_EQ(e.at(1), 1) << name;
    EXPECT_EQ(e.name(), name == "in"       ? "quad-in"
                        : name == "out"    ? "quad-out"
                        : name == "in-out" ? "quad-in-out"
                                           : name);
  }
}

TEST(Easing, TextbookValues) {
  // Hand-computed from the formulas in docs/language.md.
  EXPECT_DOUBLE_EQ(ease("quad-in").at(0.5), 0.25);
  EXPECT_DOUBLE_EQ(ease("in-out").at(0.25), 0.125);    // 2t^2
  EXPECT_DOUBLE_EQ(ease("cubic-out").at(0.5), 0.875);  // 1 - 0.5^3
  EXPECT_DOUBLE_EQ(ease("quart-in").at(0.5), 0.0625);
  EXPECT_DOUBLE_EQ(ease("quint-in-out").at(0.25), 16 * std::pow(0.25, 5));
  EXPECT_NEAR(ease("sine-in").at(0.5), 1 - std::cos(M_PI / 4), 1e-12);
  EXPECT_NEAR(ease("sine-in-out").at(0.5), 0.5, 1e-12);
  EXPECT_NEAR(ease("expo-in").at(0.5), 31.0 / 1023, 1e-12);  // (2^5 - 1) / (2^10 - 1)
  EXPECT_NEAR(ease("circ-in").at(0.6), 0.2, 1e-12);          // 1 - sqrt(1 - 0.36)
  // back-in dips below 0 before rising: (c+1)t^3 - c t^2 with c = 1.70158.
  EXPECT_NEAR(ease("back-in").at(0.5), 2.70158 * 0.125 - 1.70158 * 0.25, 1e-12);
  EXPECT_LT(ease("back-in").at(0.3), 0);
  EXPECT_GT(ease("back-out").at(0.7), 1);
  EXPECT_NEAR(ease("bounce-out").at(1 / 2.75), 1, 1e-12);  // the first landing
  // The textbook elastic-out, over 1 + 2^-11 so that the curve starts at exactly 0.
  EXPECT_NEAR(ease("elastic-out").at(0.1),
              (std::pow(2, -1) * std::sin(0.25 * 2 * M_PI / 3) + 1) / (1 + 1.0 / 2048), 1e-12);
}

TEST(Easing, CubicBezierFollowsCss) {
  const Easing e = ease("cubic-bezier(0.42, 0, 0.58, 1)");  // CSS ease-in-out
  EXPECT_EQ(e.family, EaseFamily::Bezier);
  EXPECT_NEAR(e.at(0.5), 0.5, 1e-9);  // symmetric control points
  EXPECT_LT(e.at(0.25), 0.25);
  EXPECT_NEAR(e.at(0.25) + e.at(0.75), 1, 1e-9);
  const Easing linear = ease("cubic-bezier(0, 0, 1, 1)");
  for (double t : {0.1, 0.37, 0.8}) EXPECT_NEAR(linear.at(t), t, 1e-9);
  EXPECT_EQ(e.name(), "cubic-bezier(0.42, 0, 0.58, 1)");
}

TEST(Easing, BadNamesSayWhatIsWrong) {
  EXPECT_FALSE(parse_easing("wobbly").easing);
  EXPECT_EQ(parse_easing("wobbly").message, "");  // unknown: the caller suggests a name
  EXPECT_EQ(parse_easing("cubic-bezier(1.2, 0, 0.5, 1)").message,
            "cubic-bezier's x1 is 1.2; x values must lie in [0, 1]");
  EXPECT_EQ(parse_easing("cubic-bezier(0.1, a, 0.5, 1)").message,
            "cubic-bezier's y1 'a' is not a number");
  EXPECT_EQ(parse_easing("cubic-bezier(0.1, 0.5, 1)").message,
            "cubic-bezier needs four numbers: cubic-bezier(x1, y1, x2, y2)");
  EXPECT_EQ(parse_easing("cubic-bezier 0.1").message,
            "write cubic-bezier as cubic-bezier(x1, y1, x2, y2)");
}

// The least peak speed within a tolerance, units per second, on numbers worked by hand.
TEST(SpeedWithinTolerance, MatchesTheBandsTangentsWorkedByHand) {
  auto segment = [](const char* ease, double ms, double tolerance) {
    Segment s;
    s.kind = CurveKind::Eased;
    s.easing = *parse_easing(ease).easing;
    s.start = ExactMs(1000);
    s.end = ExactMs(1000) + ExactMs::from_double(ms);
    s.from = 400;
    s.to = 500;
    s.tolerance = tolerance;
    return s;
  };
  // circ-in, A = 100 units over T: the line from the end tangent to the band's lower edge,
  // (A^2 - tol^2) / (2 tol T): (10000 - 1) / 2 = 4999.5/s over 1 s at tolerance 1, ...
  EXPECT_NEAR(speed_within_tolerance(segment("circ-in", 1000, 1), 1), 4999.5, 1e-6);
  // ... (10000 - 25) / 20 = 498.75/s over 2 s at tolerance 5, and circ-out mirrors circ-in.
  EXPECT_NEAR(speed_within_tolerance(segment("circ-in", 2000, 5), 5), 498.75, 1e-6);
  EXPECT_NEAR(speed_within_tolerance(segment("circ-out", 1000, 1), 1), 4999.5, 1e-6);
  // Pinned at both ends, no motion is slower on average than 100 units in 1 s.
  Segment line = segment("linear", 1000, 1);
  line.kind = CurveKind::Linear;
  EXPECT_NEAR(speed_within_tolerance(line, 1), 100, 1e-9);
}

TEST(Timeline, SegmentsAndHolds) {
  Timeline tl;
  tl.resize(1);
  Segment a;
  a.start = ExactMs(100);
  a.end = ExactMs(300);
  a.from = 0;
  a.to = 200;
  tl.add(0, a);
  EXPECT_FALSE(tl.value(0, 50));
  EXPECT_DOUBLE_EQ(*tl.value(0, 200), 100);
  EXPECT_DOUBLE_EQ(*tl.value(0, 1000), 200);  // holds after its last segment
  Segment h;
  h.kind = CurveKind::Hermite;
  h.start = ExactMs(0);
  h.end = ExactMs(100);
  h.from = 0;
  h.to = 100;
  h.slope_from = h.slope_to = 0;  // zero-velocity ends: the smoothstep 3u^2 - 2u^3
  EXPECT_DOUBLE_EQ(h.value(50), 50);
  EXPECT_DOUBLE_EQ(h.value(25), 100 * (3 * 0.0625 - 2 * 0.015625));
}

TEST(Timeline, ValueRangeFindsAnEaseTrueExtremeBetweenSamples) {
  // back-out is 1 + c3 (u-1)^3 + c1 (u-1)^2 with c1 = 1.70158, c3 = c1 + 1 (the CSS/Penner
  // constants). Its derivative vanishes at u - 1 = -2 c1 / (3 c3), where it peaks at
  // 1 + c3 x^3 + c1 x^2 = 1.1000 (a tenth past the target).
  const double c1 = 1.70158, c3 = c1 + 1, x = -2 * c1 / (3 * c3);
  const double peak = 1 + c3 * x * x * x + c1 * x * x;
  Segment s;
  s.start = ExactMs(1000);
  s.end = ExactMs(2000);
  s.from = 1500;
  s.to = 2450;
  s.kind = CurveKind::Eased;
  s.easing = *parse_easing("back-out").easing;
  const ValueRange r = value_range(s);
  EXPECT_NEAR(r.high, 1500 + 950 * peak, 1e-6);  // 2545.006
  EXPECT_DOUBLE_EQ(r.low, 1500);
  // Reversed, the dip below the target is the low end.
  std::swap(s.from, s.to);
  const ValueRange down = value_range(s);
  EXPECT_NEAR(down.low, 2450 - 950 * peak, 1e-6);
  EXPECT_DOUBLE_EQ(down.high, 2450);
  // A straight segment is its ends.
  s.kind = CurveKind::Linear;
  EXPECT_DOUBLE_EQ(value_range(s).low, 1500);
  EXPECT_DOUBLE_EQ(value_range(s).high, 2450);
}

TEST(Timeline, ReplacePutsPiecesInPlaceOfSegments) {
  // Servo 0: 0..100 straight 0 -> 100, 100..300 eased 100 -> 300, 300..400 straight 300 -> 0;
  // servo 1 moves over the same times, so the spans are shared between them.
  Timeline tl;
  tl.resize(2);
  auto seg = [](int start, int end, double from, double to, CurveKind kind) {
    Segment s;
    s.start = ExactMs(start);
    s.end = ExactMs(end);
    s.from = from;
    s.to = to;
    s.kind = kind;
    s.easing = *parse_easing("in-out").easing;
    return s;
  };
  tl.add(0, seg(0, 100, 0, 100, CurveKind::Linear));
  tl.add(1, seg(0, 100, 50, 60, CurveKind::Linear));
  tl.add(0, seg(100, 300, 100, 300, CurveKind::Eased));
  tl.add(1, seg(100, 300, 60, 70, CurveKind::Eased));
  tl.add(0, seg(300, 400, 300, 0, CurveKind::Linear));
  // The eased middle of servo 0 becomes two straight pieces, 100 -> 200 by 200 ms, then -> 300
  // by 300 ms; the segments around it stay where they were.
  tl.replace(
      0, 1, 1,
      {seg(100, 200, 100, 200, CurveKind::Linear), seg(200, 300, 200, 300, CurveKind::Linear)});
  ASSERT_EQ(tl.count(0), 4u);
  EXPECT_DOUBLE_EQ(*tl.value(0, 50), 50);
  EXPECT_DOUBLE_EQ(*tl.value(0, 150), 150);
  EXPECT_DOUBLE_EQ(*tl.value(0, 250), 250);
  EXPECT_DOUBLE_EQ(*tl.value(0, 350), 150);
  EXPECT_EQ(tl.segment(0, 2).kind, CurveKind::Linear);
  EXPECT_EQ(tl.start_of(0, 3), ExactMs(300));
  // Servo 1 keeps its eased middle: at 150 ms, a quarter of the way in time, in-out is 2 * 0.25^2.
  ASSERT_EQ(tl.count(1), 2u);
  EXPECT_EQ(tl.segment(1, 1).kind, CurveKind::Eased);
  EXPECT_DOUBLE_EQ(*tl.value(1, 150), 60 + 10 * 0.125);
}

}  // namespace
}  // namespace seqc::compiler
