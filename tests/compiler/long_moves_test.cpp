// Long moves (minutes to hours) are fitted from a bounded number of samples, their bands
// narrowed by a margin for the instants between them (compiler/fitting/stretch.hpp); checked
// here from the outside as fitting_test.cpp checks short ones: the controller's motion rebuilt
// from the actions alone, the intended curve from the textbook formulas (easing_reference.hpp),
// compared at every millisecond. The action counts are bounds written here: a move of T ms
// needs at least T / 30,000 actions, and a smooth curve only a few more.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "compiler/fitting/fitter.hpp"
#include "compiler/timeline/easing.hpp"
#include "tests/compiler/easing_reference.hpp"
#include "tests/compiler/fitting_check.hpp"

namespace seqc::compiler {
namespace {

using fitting_check::eased_move;
using fitting_check::Intended;
using fitting_check::Motion;

struct Worst {
  double error = 0;
  std::int64_t at = 0;
};

// The largest distance between the controller's output and the intended curve at every
// millisecond of [0, ms]; `rounds`: the output is the line rounded to a whole unit.
Worst worst_error(const FitResult& fit, const Intended& want, std::int64_t ms, bool rounds) {
  const Motion motion(fit.actions, want.from);
  Worst w;
  for (std::int64_t t = 0; t <= ms; ++t) {
    const double td = static_cast<double>(t);
    const double line = motion.at(td);
    const double out = rounds ? std::floor(line + 0.5) : line;
    const double e = std::abs(out - want.at(td));
    if (e > w.error) w = {e, t};
  }
  return w;
}

Intended intended(double from, double to, std::int64_t ms, const Easing& easing, double tol) {
  Intended want;
  want.t0 = 0;
  want.t1 = static_cast<double>(ms);
  want.from = from;
  want.to = to;
  want.easing = easing;
  want.tolerance = tol;
  return want;
}

TEST(LongMoves, EveryEaseOverTwoMinutesStaysWithinToleranceAtEveryMillisecond) {
  constexpr std::int64_t kMs = 120'000;
  for (const char* name :
       {"linear", "in-out", "sine-in-out", "expo-in-out", "back-in-out", "elastic-out",
        "elastic-in-out", "bounce-in-out", "bounce-out", "cubic-bezier(0.4, 0, 0.2, 1)"}) {
    const Easing easing = *parse_easing(name).easing;
    const FitResult fit = fit_timeline(eased_move(300, 600, kMs, easing, 1));
    const Worst w = worst_error(fit, intended(300, 600, kMs, easing, 1), kMs, false);
    EXPECT_TRUE(fit.shortfalls.empty()) << name;
    EXPECT_LE(w.error, 1.0 + 1e-9) << name << " at " << w.at << " ms";
    EXPECT_GE(fit.actions.size(), 4u) << name;
    EXPECT_LE(fit.actions.size(), 60u) << name;
    for (const FittedAction& a : fit.actions) {
      EXPECT_GE(a.time_ms, 20u) << name;
      EXPECT_LE(a.time_ms, 30000u) << name;
    }
  }
}

TEST(LongMoves, AThousandSecondElasticMoveNeedsFewActionsAndStaysWithinTolerance) {
  constexpr std::int64_t kMs = 1'000'000;
  const Easing easing = *parse_easing("elastic-out").easing;
  const FitResult fit = fit_timeline(eased_move(300, 600, kMs, easing, 1));
  const Worst w = worst_error(fit, intended(300, 600, kMs, easing, 1), kMs, false);
  EXPECT_TRUE(fit.shortfalls.empty());
  EXPECT_LE(w.error, 1.0 + 1e-9) << "at " << w.at << " ms";
  EXPECT_GE(fit.actions.size(), 34u);  // 1,000 s in actions of at most 30 s
  EXPECT_LE(fit.actions.size(), 80u);
  // The actions cover the move end to end, on whole milliseconds.
  std::int64_t at = 0;
  for (const FittedAction& a : fit.actions) {
    EXPECT_EQ(a.start_ms, at);
    at += a.time_ms;
  }
  EXPECT_EQ(at, kMs);
}

TEST(LongMoves, UnderARoundingControllerTheRoundedOutputStaysWithinTolerance) {
  constexpr std::int64_t kMs = 300'000;
  FitOptions options;
  options.model = ControllerModel::Rounds;
  for (const char* name : {"sine-in-out", "bounce-out"}) {
    const Easing easing = *parse_easing(name).easing;
    const FitResult fit = fit_timeline(eased_move(200, 700, kMs, easing, 1.5), options);
    const Worst w = worst_error(fit, intended(200, 700, kMs, easing, 1.5), kMs, true);
    EXPECT_TRUE(fit.shortfalls.empty()) << name;
    EXPECT_LE(w.error, 1.5 + 1e-9) << name << " at " << w.at << " ms";
    EXPECT_LE(fit.actions.size(), 80u) << name;
  }
}

}  // namespace
}  // namespace seqc::compiler
