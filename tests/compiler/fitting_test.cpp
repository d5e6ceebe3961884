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
#include "tests/compiler/lang_test_util.hpp"

namespace seqc::compiler {
namespace {

constexpr std::int64_t kMinActionMs = 20;
constexpr double kHoldTolerance = 1;  // the tolerance of the hold before the curve

// The controller's motion of servo 0, rebuilt from the actions alone: during each action a
// straight line from where the servo is to the action's target, or a hold if the action does
// not name it.
class Motion {
 public:
  Motion(const std::vector<FittedAction>& actions, double start_value) {
    double pos = start_value;
    for (const FittedAction& a : actions) {
      double to = pos;
      for (const FittedTarget& x : a.targets) {
        if (x.servo == 0) to = x.position;
      }
      pieces_.push_back(
          {static_cast<double>(a.start_ms), static_cast<double>(a.start_ms + a.time_ms), pos, to});
      pos = to;
    }
    start_value_ = start_value;
  }
  double at(double t) const {
    const auto it = std::lower_bound(pieces_.begin(), pieces_.end(), t,
                                     [](const Piece& p, double v) { return p.end < v; });
    if (it == pieces_.end()) return pieces_.empty() ? start_value_ : pieces_.back().to;
    if (t <= it->start) return it->from;
    return it->from + (it->to - it->from) * (t - it->start) / (it->end - it->start);
  }

 private:
  struct Piece {
    double start, end, from, to;
  };
  std::vector<Piece> pieces_;
  double start_value_ = 0;
};

// What the author meant: `from` held until the curve starts at t0, then the curve to t1, then
// `to` held; computed from the reference formulas.
struct Intended {
  double t0 = 0, t1 = 0, from = 0, to = 0, tolerance = 1;
  bool hermite = false;
  double slope_from = 0, slope_to = 0;  // Hermite, units per ms
  Easing easing;                        // otherwise

  double at(double t) const {
    if (t <= t0) return from;
    if (t >= t1) return to;
    const double u = (t - t0) / (t1 - t0);
    if (!hermite) return from + (to - from) * testing::ease_ref::at(easing, u);
    // A cubic Hermite piece is the Bezier curve with inner control points a third of the way
    // along each end's tangent.
    const double h = t1 - t0;
    const double p1 = from + slope_from * h / 3, p2 = to - slope_to * h / 3;
    const double v = 1 - u;
    return v * v * v * from + 3 * v * v * u * p1 + 3 * v * u * u * p2 + u * u * u * to;
  }
  double tolerance_at(std::int64_t t) const {
    return static_cast<double>(t) < t0 ? kHoldTolerance : tolerance;
  }
};

// Whether a straight line fits within tol of want at every point of a window (offsets 0..n-1),
// decided exactly: with a and b the line's values at the window's ends, each point bounds b
// from below and above by a linear function of a; eliminating b (Fourier-Motzkin) leaves
// bounds on a.
bool one_line_fits(const std::vector<double>& want, const std::vector<double>& tol) {
  const std::size_t n = want.size();
  if (n <= 2) return true;
  double a_lo = want[0] - tol[0], a_hi = want[0] + tol[0];
  struct Bound {
    double c, k;  // b >= c - k a (lower) or b <= c - k a (upper)
  };
  std::vector<Bound> lower, upper;
  for (std::size_t t = 1; t < n; ++t) {
    const double lambda = static_cast<double>(t) / static_cast<double>(n - 1);
    const double k = (1 - lambda) / lambda;
    lower.push_back({(want[t] - tol[t]) / lambda, k});
    upper.push_back({(want[t] + tol[t]) / lambda, k});
  }
  for (const Bound& l : lower) {
    for (const Bound& u : upper) {
      // l.c - l.k a <= u.c - u.k a  <=>  (l.k - u.k) a >= l.c - u.c
      const double k = l.k - u.k, c = l.c - u.c;
      if (k > 0) {
        a_lo = std::max(a_lo, c / k);
      } else if (k < 0) {
        a_hi = std::min(a_hi, c / k);
      } else if (c > 0) {
        return false;
      }
    }
  }
  return a_lo <= a_hi;
}

// Whether some motion the controller could make stays within tolerance of the intended curve
// at every millisecond of [l, r]: straight lines between breakpoints on the millisecond grid,
// at least kMinActionMs apart, each breakpoint at any whole unit within tolerance of the
// intended position there, and at a knot (the start, and each end of the curve: segment
// boundaries stay action boundaries) at the intended position rounded. The line entering the
// window and the one leaving it are allowed any slope and length (their other ends lie
// outside), so `false` proves that no motion does.
bool followable(const Intended& c, std::int64_t l, std::int64_t r) {
  const std::size_t n = static_cast<std::size_t>(r - l + 1);
  std::vector<double> want(n), tol(n);
  std::vector<int> lowest(n), highest(n);  // the whole units a breakpoint may be at
  std::vector<char> knot(n);
  std::size_t first_knot = n;
  for (std::size_t i = 0; i < n; ++i) {
    const std::int64_t t = l + static_cast<std::int64_t>(i);
    const double td = static_cast<double>(t);
    want[i] = c.at(td);
    tol[i] = c.tolerance_at(t) + 1e-7;  // generous: a proof must not hang on rounding noise
    knot[i] = t == 0 || td == c.t0 || td == c.t1;
    if (knot[i]) {
      lowest[i] = highest[i] = static_cast<int>(std::lround(want[i]));
    } else {
      lowest[i] = static_cast<int>(std::ceil(want[i] - tol[i]));
      highest[i] = static_cast<int>(std::floor(want[i] + tol[i]));
    }
    if (knot[i] && first_knot == n) first_knot = i;
  }
  if (first_knot == n && one_line_fits(want, tol)) return true;  // no breakpoint inside
  // reach[q][j]: a breakpoint at q, at lowest[q] + j, ends a motion within tolerance from l.
  std::vector<std::vector<char>> reach(n);
  for (std::size_t q = 0; q < n; ++q) {
    reach[q].assign(static_cast<std::size_t>(std::max(0, highest[q] - lowest[q] + 1)), 0);
  }
  // The first breakpoint inside, entered at any slope from outside (not across a knot).
  for (std::size_t q = 0; q < n && q <= first_knot; ++q) {
    for (int v = lowest[q]; v <= highest[q]; ++v) {
      double lo = -std::numeric_limits<double>::infinity(), hi = -lo;
      for (std::size_t t = q; t-- > 0 && lo <= hi;) {
        const double span = static_cast<double>(q - t);
        lo = std::max(lo, (v - want[t] - tol[t]) / span);
        hi = std::min(hi, (v - want[t] + tol[t]) / span);
      }
      reach[q][static_cast<std::size_t>(v - lowest[q])] =
          lo <= hi && std::abs(v - want[q]) <= tol[q];
    }
  }
  for (std::size_t p = 0; p < n; ++p) {
    for (int u = lowest[p]; u <= highest[p]; ++u) {
      if (!reach[p][static_cast<std::size_t>(u - lowest[p])]) continue;
      if (p == n - 1) return true;
      // Lines from (p, u): the slopes that keep every instant so far within tolerance.
      double lo = -std::numeric_limits<double>::infinity(), hi = -lo;
      for (std::size_t q = p + 1; q < n; ++q) {
        const double span = static_cast<double>(q - p);
        if (q - p >= static_cast<std::size_t>(kMinActionMs)) {
          for (int v = lowest[q]; v <= highest[q]; ++v) {
            const double slope = (v - u) / span;
            if (slope >= lo && slope <= hi && std::abs(v - want[q]) <= tol[q]) {
              reach[q][static_cast<std::size_t>(v - lowest[q])] = 1;
            }
          }
        }
        lo = std::max(lo, (want[q] - tol[q] - u) / span);
        hi = std::min(hi, (want[q] + tol[q] - u) / span);
        if (lo > hi || knot[q]) break;
        if (q == n - 1) return true;  // the line leaving the window from (p, u)
      }
    }
  }
  return false;
}

// A shortfall at `at` is proven when no motion follows the curve within tolerance over some
// window around it: the smallest of a few widths is taken, all of them short.
bool shortfall_proven(const Intended& c, std::int64_t at, std::int64_t end) {
  for (std::int64_t half : {30, 60, 120}) {
    if (!followable(c, std::max<std::int64_t>(0, at - half), std::min(end, at + half))) {
      return true;
    }
  }
  return false;
}

Timeline one_curve(const Segment& seg) {
  Timeline tl;
  tl.resize(1);
  Segment start;  // where the servo is before the curve: a short hold
  start.kind = CurveKind::Hold;
  start.start = ExactMs(0);
  start.end = seg.start;
  start.from = start.to = seg.from;
  start.tolerance = kHoldTolerance;
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
// never do; three do (boundaries at 20 and 40: targets 2 and 8, each chord within 0.5 + 0.5).
TEST(Fitting, FreeEndPointsSaveAnActionOnAHandWorkedCurve) {
  Segment seg;
  seg.start = ExactMs(0);
  seg.end = ExactMs(60);
  seg.from = 0;
  seg.to = 18;
  seg.kind = CurveKind::Eased;
  seg.easing = *parse_easing("quad-in").easing;
  seg.tolerance = 1;
  Timeline tl;
  tl.resize(1);
  tl.add(0, seg);
  tl.end = ExactMs(60);
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
        Segment seg;
        seg.start = ExactMs(0);
        seg.end = ExactMs(ms);
        seg.from = 50;
        seg.to = 450;
        seg.kind = CurveKind::Eased;
        seg.easing = *parse_easing(name).easing;
        seg.tolerance = tol;
        Timeline tl;
        tl.resize(1);
        tl.add(0, seg);
        tl.end = ExactMs(ms);
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

// The controller model: a fit for a controller that rounds (or truncates) its output to whole
// units keeps that output within tolerance at every millisecond; the same curves fitted for
// the straight line do not, put out that way, so the setting is what keeps the promise.
TEST(Fitting, TheControllerModelIsWhatTheToleranceHoldsFor) {
  EXPECT_EQ(controller_output(ControllerModel::StraightLine, 2.5), 2.5);
  EXPECT_EQ(controller_output(ControllerModel::Rounds, 2.5), 3);
  EXPECT_EQ(controller_output(ControllerModel::Rounds, 2.49), 2);
  EXPECT_EQ(controller_output(ControllerModel::Truncates, 2.99), 2);
  auto output = [](ControllerModel model, double line) {
    return model == ControllerModel::Rounds ? std::floor(line + 0.5) : std::trunc(line);
  };
  for (ControllerModel model : {ControllerModel::Rounds, ControllerModel::Truncates}) {
    int straight_misses = 0;
    for (const char* name : {"sine-in-out", "quad-in-out", "cubic-out", "back-in-out"}) {
      Segment seg;
      seg.start = ExactMs(0);
      seg.end = ExactMs(1500);
      seg.from = 300;
      seg.to = 420;
      seg.kind = CurveKind::Eased;
      seg.easing = *parse_easing(name).easing;
      seg.tolerance = 1;
      Timeline tl;
      tl.resize(1);
      tl.add(0, seg);
      tl.end = ExactMs(1500);
      Intended want;
      want.t1 = 1500;
      want.from = 300;
      want.to = 420;
      want.tolerance = 1;
      want.easing = seg.easing;
      FitOptions options;
      options.model = model;
      const FitResult fit = fit_timeline(tl, options);
      EXPECT_TRUE(fit.shortfalls.empty()) << name;
      const Motion motion(fit.actions, 300);
      double worst = 0;
      for (int t = 0; t <= 1500; ++t) {
        const double err = std::abs(output(model, motion.at(t)) - want.at(t));
        EXPECT_LE(err, 1 + 1e-9) << name << " at " << t;
        worst = std::max(worst, err);
      }
      EXPECT_NEAR(fit.max_error, worst, 1e-6) << name;
      const Motion straight(fit_timeline(tl).actions, 300);
      for (int t = 0; t <= 1500; ++t) {
        if (std::abs(output(model, straight.at(t)) - want.at(t)) > 1 + 1e-9) {
          ++straight_misses;
          break;
        }
      }
    }
    EXPECT_GT(straight_misses, 0);
  }
}

// Every built-in profile fits for the straight line between whole-unit targets: what the
// protocol document describes; docs/language.md says why.
TEST(Fitting, BuiltInProfilesFitForTheStraightLine) {
  for (const char* name : {"xarm", "bus", "lsc-16", "lsc-32", "lsc-6"}) {
    const RobotProfile* p = find_profile(name);
    ASSERT_NE(p, nullptr) << name;
    EXPECT_EQ(p->controller, ControllerModel::StraightLine) << name;
  }
}

}  // namespace
}  // namespace seqc::compiler
