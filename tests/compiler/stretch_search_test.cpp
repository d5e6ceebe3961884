// How fitting searches a stretch, checked from the outside as in fitting_test.cpp
// (fitting_check.hpp): a curve repeated with another tolerance is not given the first one's fit
// (searches are reused only for an equal stretch), and stretches too long to search whole
// within the work budget are cut and still fitted within tolerance.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>
#include <utility>
#include <vector>

#include "compiler/fitting/fitter.hpp"
#include "compiler/timeline/easing.hpp"
#include "tests/bench/fit_reference.hpp"
#include "tests/compiler/fitting_check.hpp"

namespace seqc::compiler {
namespace {

using namespace fitting_check;

// A curve repeated with another tolerance is fitted for its own: the same sine-in-out, 400 to
// 460 over 600 ms, at tolerance 1 and (after a straight return) at tolerance 2, in either
// order, holds around the return so that each part's ends stay action boundaries. Each part
// needs the exact fewest actions of that curve at its own tolerance (the benchmark's exhaustive
// reference), whatever the other part needed.
TEST(Fitting, ARepeatedCurveWithAnotherToleranceIsFittedForItsOwn) {
  const Easing easing = *parse_easing("sine-in-out").easing;
  fit_reference::Piece piece;
  piece.t1 = 600;
  piece.from = 400;
  piece.to = 460;
  piece.easing = easing;
  const int at_1 = fit_reference::free_minimum(piece, 600, 1);
  const int at_2 = fit_reference::free_minimum(piece, 600, 2);
  ASSERT_NE(at_1, at_2);  // so that a fit reused from the other part would show
  for (const auto& [first, second] : {std::pair{1.0, 2.0}, std::pair{2.0, 1.0}}) {
    Timeline tl;
    tl.resize(1);
    tl.add(0, segment(0, 600, 400, 460, CurveKind::Eased, easing, first));
    tl.add(0, segment(600, 700, 460, 460, CurveKind::Hold, easing, 1));
    tl.add(0, segment(700, 900, 460, 400, CurveKind::Linear, easing, 1));
    tl.add(0, segment(900, 1000, 400, 400, CurveKind::Hold, easing, 1));
    tl.add(0, segment(1000, 1600, 400, 460, CurveKind::Eased, easing, second));
    tl.end = ExactMs(1600);
    const FitResult fit = fit_timeline(tl);
    EXPECT_TRUE(fit.shortfalls.empty());
    auto actions_in = [&](std::uint32_t a, std::uint32_t b) {
      return std::count_if(fit.actions.begin(), fit.actions.end(), [&](const FittedAction& x) {
        return x.start_ms >= a && x.start_ms + x.time_ms <= b;
      });
    };
    EXPECT_EQ(actions_in(0, 600), first == 1 ? at_1 : at_2) << "tolerance " << first;
    EXPECT_EQ(actions_in(1000, 1600), second == 1 ? at_1 : at_2) << "tolerance " << second;
  }
}

// A curve too long to search whole within the work budget (sine-in-out, 400 to 460 over 10 s at
// tolerance 2: about 5 values x 10,000 ms x lines of seconds, past 40 million window updates)
// is cut into parts searched on their own, and still fitted within tolerance at every
// millisecond of the textbook curve, with no more actions than the fit on the curve.
TEST(Fitting, ACurveTooLongToSearchWholeIsCutAndStillWithinTolerance) {
  const Easing easing = *parse_easing("sine-in-out").easing;
  const Timeline tl = eased_move(400, 460, 10000, easing, 2);
  const FitResult fit = fit_timeline(tl);
  EXPECT_TRUE(fit.shortfalls.empty());
  const Motion motion(fit.actions, 400);
  for (int t = 0; t <= 10000; ++t) {
    const double curve = 400 + 60 * (1 - std::cos(std::numbers::pi * t / 10000.0)) / 2;
    ASSERT_LE(std::abs(motion.at(t) - curve), 2 + 1e-6) << t << " ms";
  }
  FitOptions on_curve;
  on_curve.free_end_points = false;
  EXPECT_LE(fit.actions.size(), fit_timeline(tl, on_curve).actions.size());
}

// Two servos moving together over 10 s (sine-in-out by 60 and quad-in-out by 45 at tolerance
// 2) are too many lines to search whole within the work budget; the stretch is cut into parts
// searched on their own, and the fit stays within tolerance at every millisecond of the
// textbook curves with no more actions than a plain fit worked here: five equal actions of
// 2 s, each servo's targets its curve rounded (checked here to keep both within 2).
TEST(Fitting, ServosTooLongToSearchTogetherAreCutAndStillWithinTolerance) {
  const int ms = 10000;
  auto sine = [&](double t) { return 400 + 60 * (1 - std::cos(std::numbers::pi * t / ms)) / 2; };
  auto quad = [&](double t) {
    const double u = t / ms;
    return 400 + 45 * (u < 0.5 ? 2 * u * u : 1 - (2 - 2 * u) * (2 - 2 * u) / 2);
  };
  Timeline tl;
  tl.resize(2);
  tl.add(0, segment(0, ms, 400, 460, CurveKind::Eased, *parse_easing("sine-in-out").easing, 2));
  tl.add(1, segment(0, ms, 400, 445, CurveKind::Eased, *parse_easing("quad-in-out").easing, 2));
  tl.end = ExactMs(ms);
  const std::vector<std::function<double(double)>> curves = {sine, quad};
  // The plain fit: both servos within 2 along the lines between their rounded curves at every
  // 2,000th ms.
  for (const auto& curve : curves) {
    for (int a = 0; a < ms; a += 2000) {
      const double from = std::round(curve(a)), to = std::round(curve(a + 2000));
      for (int t = a; t <= a + 2000; ++t) {
        ASSERT_LE(std::abs(from + (to - from) * (t - a) / 2000.0 - curve(t)), 2);
      }
    }
  }
  const FitResult fit = fit_timeline(tl);
  EXPECT_TRUE(fit.shortfalls.empty());
  EXPECT_LE(fit.actions.size(), 5u);
  for (std::size_t s = 0; s < 2; ++s) {
    const Motion motion(fit.actions, 400, s);
    for (int t = 0; t <= ms; ++t) {
      ASSERT_LE(std::abs(motion.at(t) - curves[s](t)), 2 + 1e-6) << "servo " << s << ", " << t;
    }
  }
}

}  // namespace
}  // namespace seqc::compiler
