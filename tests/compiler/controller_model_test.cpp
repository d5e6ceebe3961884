// The controller model, checked from the outside as in fitting_test.cpp (fitting_check.hpp):
// the tolerance is held under the model the fit was made for (and not under another), a file
// chooses its board's model, and every built-in profile uses the straight line.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "compiler/fitting/fitter.hpp"
#include "compiler/frontend/profiles.hpp"
#include "compiler/timeline/easing.hpp"
#include "tests/compiler/fitting_check.hpp"
#include "tests/compiler/lang_test_util.hpp"

namespace seqc::compiler {
namespace {

using namespace fitting_check;

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
      const Easing easing = *parse_easing(name).easing;
      const Timeline tl = eased_move(300, 420, 1500, easing, 1);
      Intended want;
      want.t1 = 1500;
      want.from = 300;
      want.to = 420;
      want.tolerance = 1;
      want.easing = easing;
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

// A file names its board's model in `robot:`; the program is fitted for it and carries it, so
// that `simulate --compare` measures the same motion.
TEST(Fitting, AFileChoosesItsControllerModel) {
  const std::string head = "robot: {profile: xarm, controller: ";
  const std::string body =
      "}\nsequence:\n  - move: {claw: 300}\n    time: 500ms\n"
      "  - move: {claw: 420}\n    time: 1500ms\n    ease: sine-in-out\n";
  for (const auto& [word, model] : std::vector<std::pair<std::string, ControllerModel>>{
           {"straight-line", ControllerModel::StraightLine},
           {"rounds", ControllerModel::Rounds},
           {"truncates", ControllerModel::Truncates}}) {
    const CompileOutput out = testing::compile_text(head + word + body);
    const ServoProgram& p = testing::program_of(out);
    EXPECT_EQ(p.controller, model) << word;
    // The claw (bus id 1) under that model, at every millisecond of the eased move, against
    // (1 - cos(pi t)) / 2 from 300 to 420, written here.
    std::vector<FittedAction> actions;
    for (const Keyframe& k : p.keyframes) {
      if (k.start_ms < 500) continue;
      FittedAction a;
      a.start_ms = k.start_ms - 500;
      a.time_ms = k.time_ms;
      for (const auto& t : k.targets) {
        if (t.id == 1) a.targets.push_back({0, t.position});
      }
      actions.push_back(a);
    }
    const Motion motion(actions, 300);
    for (int t = 0; t <= 1500; ++t) {
      const double line = motion.at(t);
      const double out_now = model == ControllerModel::Rounds      ? std::floor(line + 0.5)
                             : model == ControllerModel::Truncates ? std::trunc(line)
                                                                   : line;
      const double want = 300 + 120 * (1 - std::cos(std::numbers::pi * t / 1500.0)) / 2;
      EXPECT_LE(std::abs(out_now - want), 1 + 1e-9) << word << " at " << t;
    }
  }
  EXPECT_EQ(testing::messages(testing::compile_text(head + "round" + body)),
            std::vector<std::string>{
                "1:36 error: unknown controller model 'round'; did you mean 'rounds'? "
                "(straight-line: the exact line between whole-unit targets; rounds or "
                "truncates: that line rounded or truncated to whole units)"});
}

// Every built-in profile fits for the straight line between whole-unit targets: what the
// protocol document describes; docs/language.md says why.
TEST(Fitting, BuiltInProfilesFitForTheStraightLine) {
  for (const char* name : {"xarm", "bus", "lsc-16", "lsc-32", "lsc-6", "learm"}) {
    const RobotProfile* p = find_profile(name);
    ASSERT_NE(p, nullptr) << name;
    EXPECT_EQ(p->controller, ControllerModel::StraightLine) << name;
  }
}

}  // namespace
}  // namespace seqc::compiler
