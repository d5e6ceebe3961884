// The checks a move's motion gets: each easing's peak speed against its true derivative (the
// figures worked out below from the formulas of docs/language.md), `through` holding a servo
// between equal waypoints, the first move of a group from the far end of the servo's limits,
// one warning for the servos that break a limit alike, a note naming the section performance
// a warning comes from, the valid names listed for an unknown robot or easing, and a show file
// given to the single-robot front end.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "tests/compiler/lang_test_util.hpp"

namespace seqc::compiler {
namespace {

using testing::compile_text;
using testing::diagnostics_of;
using testing::messages;
using testing::program_of;

constexpr double kPi = std::numbers::pi;
constexpr double kLn2 = std::numbers::ln2;

// Peak |d ease / dt| of each curve on [0, 1], written out from its formula.
struct Peak {
  const char* family;
  double in, out, in_out;  // infinity: the curve is vertical somewhere
};

std::vector<Peak> peaks() {
  const double inf = std::numeric_limits<double>::infinity();
  // expo-in = (2^(10t) - 1) / 1023: its slope 10 ln2 2^(10t) / 1023 is largest at t = 1. Its
  // in-out runs in(2t)/2, whose slope in'(2t) reaches the same at t = 1/2.
  const double expo = 10 * kLn2 * 1024 / 1023;
  // back-in = (c + 1)t^3 - ct^2: slope 3(c + 1)t^2 - 2ct, largest in size at t = 1: c + 3
  // (its dip, -c^2 / (3(c + 1)) at t = c / (3(c + 1)), is smaller). In-out uses c * 1.525.
  const double c = 1.70158;
  // elastic-in = (e(t) + 2^-11) / (1 + 2^-11) with e(t) = -2^(10t - 10) sin((10t - 10.75) w),
  // w = 2pi/3. e'(t) = -10 A 2^(10t - 10) sin(theta + phi) with A = sqrt(ln2^2 + w^2),
  // tan phi = w / ln2, theta = (10t - 10.75) w; |e'| is stationary where theta = -2 phi, at
  // t = 0.9555 (the next stationary point lies past t = 1), and there |e'| = 10 A sin(phi)
  // 2^(10t - 10) = 10 w 2^(0.75 - 2 phi / w). -out mirrors -in, so its peak is the same.
  const double w = 2 * kPi / 3;
  const double phi = std::atan(w / kLn2);
  const double elastic = 10 * w * std::pow(2, 0.75 - 2 * phi / w) / (1 + 1.0 / 2048);
  // elastic-in-out: the same with v = 2pi/4.5 and 11.125 on each half, G(u) = (g(u) - g0) /
  // (1 - g0), g0 = 2^-10 sin(pi/18); the slope of G(2t)/2 is G'(2t), stationary where
  // (10u - 11.125) v = -2 psi, tan psi = v / ln2: 10 v 2^(1.125 - 2 psi / v) / (1 - g0).
  const double v = 2 * kPi / 4.5;
  const double psi = std::atan(v / kLn2);
  const double elastic_in_out =
      10 * v * std::pow(2, 1.125 - 2 * psi / v) / (1 - std::sin(kPi / 18) / 1024);
  // bounce-out's first arc 7.5625t^2 ends at t = 1/2.75 with slope 2 * 7.5625 / 2.75 = 5.5; the
  // later arcs are flatter (2.75, 1.375, 0.6875 at their ends).
  const double bounce = 2 * 7.5625 / 2.75;
  return {
      {"sine", kPi / 2, kPi / 2, kPi / 2},  // sin(pi t/2) pi/2 and sin(pi t) pi/2
      {"quad", 2, 2, 2},                    // n t^(n-1) at t = 1; in-out: in'(2t) at t = 1/2
      {"cubic", 3, 3, 3},
      {"quart", 4, 4, 4},
      {"quint", 5, 5, 5},
      {"expo", expo, expo, expo},
      {"circ", inf, inf, inf},  // 1 - sqrt(1 - t^2) is vertical at t = 1
      {"back", c + 3, c + 3, c * 1.525 + 3},
      {"elastic", elastic, elastic, elastic_in_out},
      {"bounce", bounce, bounce, bounce},
  };
}

// 100 units over 2 s: the average speed is 50/s, so a curve peaks at 50 times its peak slope.
std::string one_eased_move(const std::string& ease, const std::string& max_speed) {
  return "robot:\n  profile: xarm\n  servos:\n    base: {max_speed: " + max_speed +
         "}\nsequence:\n  - move: {base: 450}\n    time: 20s\n  - move: {base: 550}\n"
         "    time: 2s\n    ease: " +
         ease + "\n";
}

TEST(MotionChecks, EachEasingPeaksAtItsTrueDerivative) {
  for (const Peak& p : peaks()) {
    for (const auto& [mode, slope] :
         {std::pair{"-in", p.in}, std::pair{"-out", p.out}, std::pair{"-in-out", p.in_out}}) {
      const std::string ease = std::string(p.family) + mode;
      // A max_speed of 1/s: every curve breaks it, and the warning says its peak.
      const auto out = compile_text(one_eased_move(ease, "1/s"));
      std::string warning;
      for (const std::string& m : messages(out)) {
        if (m.rfind("8:5 warning: 100 in 2000ms", 0) == 0) warning = m;
      }
      const std::string head = "8:5 warning: 100 in 2000ms ";
      if (std::isinf(slope)) {
        // Vertical: judged within the tolerance (1). circ-in and circ-out need
        // (100^2 - 1^2) / (2 x 1 x 2 s) = 2499.75/s, printed to the hundredth; circ-in-out less.
        const std::string needs = ease == "circ-in-out" ? "" : "needs at least 2499.75/s";
        if (!needs.empty()) {
          EXPECT_EQ(warning, head + needs + " on this " + ease +
                                 " curve within a tolerance of 1, above base's 1/s");
        } else {
          EXPECT_EQ(warning.rfind(head + "needs at least ", 0), 0u) << warning;
        }
        continue;
      }
      const std::string tail = " on this " + ease + " curve, above base's 1/s";
      ASSERT_EQ(warning.substr(0, head.size()), head) << ease << ": " << diagnostics_of(out);
      ASSERT_GE(warning.size(), head.size() + tail.size()) << warning;
      EXPECT_EQ(warning.substr(warning.size() - tail.size()), tail) << warning;
      const std::string middle =
          warning.substr(head.size(), warning.size() - head.size() - tail.size());
      ASSERT_EQ(middle.rfind("peaks at ", 0), 0u) << warning;
      const double reported = std::stod(middle.substr(9));
      // Printed to the unit: within half a unit, plus a thousandth for the peak's search.
      EXPECT_NEAR(reported, 50 * slope, 0.5 + 50 * slope * 1e-3) << ease << ": " << warning;
    }
  }
}

TEST(MotionChecks, MovesBelowTheirTruePeakCheckCleanWhenStrict) {
  // Every easing but circ (vertical: judged within the tolerance) peaks below 800/s on 100 units
  // in 2 s:
  // the fastest, elastic-in/out, at 50 x 15.39 = 769.5/s. The first move comes from at most
  // 1000 - 450 = 550 units away, 0.69 s at 800/s, and takes 1 s.
  std::string text =
      "robot:\n  profile: xarm\n  servos:\n    base: {max_speed: 800/s}\nsequence:\n"
      "  - move: {base: 450}\n    time: 1s\n";
  int to = 550;
  for (const Peak& p : peaks()) {
    if (std::string(p.family) == "circ") continue;
    for (const char* mode : {"-in", "-out", "-in-out"}) {
      text += "  - move: {base: " + std::to_string(to) + "}\n    time: 2s\n    ease: " + p.family +
              mode + "\n";
      to = to == 550 ? 450 : 550;
    }
  }
  const auto out = compile_text(text, /*strict=*/true);
  EXPECT_TRUE(out.program) << diagnostics_of(out);
  EXPECT_EQ(diagnostics_of(out), "");
}

TEST(MotionChecks, ExpoOutOfAHundredUnitsInTwoSecondsPeaksAt347PerSecond) {
  // 50/s x 10 ln2 x 1024/1023 = 346.9/s, at the curve's start.
  EXPECT_EQ(messages(compile_text(one_eased_move("expo-out", "300/s"))),
            std::vector<std::string>{"8:5 warning: 100 in 2000ms peaks at 347/s on this expo-out "
                                     "curve, above base's 300/s"});
  EXPECT_EQ(messages(compile_text(one_eased_move("expo-out", "347/s"))),
            std::vector<std::string>{});
}

TEST(MotionChecks, ThroughHoldsAServoBetweenEqualWaypoints) {
  const auto out = compile_text(R"(robot: xarm
sequence:
  - move: {base: 500, elbow: 500}
    time: 1s
  - through:
      - pose: {base: 750, elbow: 600}
        time: 1s
      - pose: {elbow: 700}
        time: 1s
      - pose: {base: 250, elbow: 500}
        time: 1s
)");
  const ServoProgram& program = program_of(out);
  const Timeline& tl = program.timeline;
  const std::size_t base = 6 - 1, elbow = 4 - 1;  // xArm ids 6 and 4, in id order
  ASSERT_EQ(tl.count(base), 4u) << diagnostics_of(out);
  // base: 500 at 1 s, 750 at 2 s and 3 s, 250 at 4 s. Both 750s get slope 0, so between them
  // it stays at exactly 750; the ends are smoothsteps, half way at their middles.
  for (double t = 2000; t <= 3000; t += 10) EXPECT_EQ(*tl.value(base, t), 750) << t;
  EXPECT_DOUBLE_EQ(*tl.value(base, 1500), 625);
  EXPECT_DOUBLE_EQ(*tl.value(base, 3500), 500);
  // elbow 500, 600, 700, 500 keeps the documented slopes: at 2 s (700 - 500) / 2000ms = 0.1
  // per ms, at 3 s (500 - 600) / 2000ms = -0.05. Half way from 2 s to 3 s the Hermite basis
  // gives 0.5 x 600 + 0.125 x 1000 x 0.1 + 0.5 x 700 - 0.125 x 1000 x (-0.05) = 668.75.
  EXPECT_NEAR(*tl.value(elbow, 2500), 668.75, 1e-3);
  EXPECT_NEAR(tl.segment(elbow, 2).slope_from, 0.1, 1e-6);
  EXPECT_NEAR(tl.segment(elbow, 2).slope_to, -0.05, 1e-6);
}

TEST(MotionChecks, ThroughHoldsAServoWrittenTwiceAlike) {
  const auto out = compile_text(R"(robot: xarm
sequence:
  - move: {base: 500}
    time: 1s
  - through:
      - pose: {base: 750}
        time: 1s
      - pose: {base: 750}
        time: 500ms
      - pose: {base: 500}
        time: 1s
)");
  const Timeline& tl = program_of(out).timeline;
  for (double t = 2000; t <= 2500; t += 5) EXPECT_EQ(*tl.value(5, t), 750) << t;
}

TEST(MotionChecks, TheFirstMoveIsCheckedFromTheFarEndOfTheLimits) {
  // base 0..1000 at 800/s moving to 200: it may start at 1000, 800 units away, 1 s.
  const auto out = compile_text(R"(robot:
  profile: xarm
  servos:
    base: {max_speed: 800/s}
sequence:
  - move: {base: 200}
    time: 500ms
  - move: {base: 210}
    time: 500ms
)");
  EXPECT_EQ(messages(out),
            std::vector<std::string>{"6:5 warning: first move of 'base' may start anywhere in "
                                     "0..1000; from 1000 it needs 1 s at max_speed 800/s; this "
                                     "move takes 0.5 s"});
  // 1 s is enough; 999ms is not (and the time named is rounded up to the hundredth).
  const std::string slow =
      "robot:\n  profile: xarm\n  servos:\n    base: {max_speed: 800/s}\n"
      "sequence:\n  - move: {base: 200}\n    time: ";
  EXPECT_EQ(messages(compile_text(slow + "1s\n")), std::vector<std::string>{});
  EXPECT_EQ(messages(compile_text(slow + "999ms\n")).size(), 1u);
  // 300 units at 800/s: 0.375 s, named as 0.38 s.
  EXPECT_EQ(messages(compile_text(
                "robot:\n  profile: xarm\n  servos:\n    base: {min: 200, max: 500, max_speed: "
                "800/s, home: 300}\nsequence:\n  - move: {base: 500}\n    time: 100ms\n")),
            std::vector<std::string>{"6:5 warning: first move of 'base' may start anywhere in "
                                     "200..500; from 200 it needs 0.38 s at max_speed 800/s; this "
                                     "move takes 0.1 s"});
}

// A first move that starts later than 0 ms (`at: 200ms` in a track, 1.2 s into the sequence)
// is checked like one at the start: base 0..1000 at 800/s moving to 200 may come from 1000, 800
// units away, 1 s; the move takes 500 ms (200..700 of the block), too fast; 1 s (200..1200) is
// enough. shoulder gets its position first (to 500 in 1 s: from 0 at the xArm's 1562.5/s it
// needs 0.32 s), so its track is no first move. Line 13 col 11 is base's `- move:`.
TEST(MotionChecks, AFirstMoveStartingLaterThanZeroIsCheckedToo) {
  const auto file = [](const std::string& time) {
    return "robot:\n"
           "  profile: xarm\n"
           "  servos:\n"
           "    base: {max_speed: 800/s}\n"
           "sequence:\n"
           "  - move: {shoulder: 500}\n"
           "    time: 1s\n"
           "  - together:\n"
           "      a:\n"
           "        - move: {shoulder: 600}\n"
           "          time: 1200ms\n"
           "      b:\n"
           "        - move: {base: 200}\n"
           "          time: " +
           time +
           "\n"
           "          at: 200ms\n";
  };
  EXPECT_EQ(messages(compile_text(file("500ms"))),
            std::vector<std::string>{"13:11 warning: first move of 'base' may start anywhere in "
                                     "0..1000; from 1000 it needs 1 s at max_speed 800/s; this "
                                     "move takes 0.5 s"});
  EXPECT_EQ(messages(compile_text(file("1s"))), std::vector<std::string>{});
}

// base's first move (no position before it) runs 0..1100 ms while the other track's move ends
// at 200 ms, a boundary of every servo's actions. The controller can only be told base's end:
// sending it in the 200 ms action would take base all the way in 200 ms (5000/s). So base is
// left out of that action and named only in the one ending with its move, 200..1100 ms, where
// it goes to 1000 in 900 ms, arriving at its written 1.1 s. From 0, 1000 units at 1000/s need
// 1 s: within the written 1.1 s (no first-move warning for the move as written), more than the
// 0.9 s it gets.
TEST(MotionChecks, AFirstMoveCutByAnotherTrackArrivesAtItsWrittenTime) {
  const auto out = compile_text(R"(robot:
  profile: xarm
  servos:
    base: {max_speed: 1000/s}
sequence:
  - together:
      a:
        - move: {shoulder: 600}
          time: 200ms
        - move: {shoulder: 700}
          time: 1s
      b:
        - move: {base: 1000}
          time: 1.1s
)");
  const ServoProgram& p = program_of(out);
  ASSERT_EQ(p.keyframes.size(), 3u);
  // shoulder is id 5, base id 6.
  EXPECT_EQ(p.keyframes[0].start_ms, 0u);
  EXPECT_EQ(p.keyframes[0].time_ms, 200u);
  ASSERT_EQ(p.keyframes[0].targets.size(), 1u);
  EXPECT_EQ(p.keyframes[0].targets[0].id, 5);
  EXPECT_EQ(p.keyframes[1].start_ms, 200u);
  EXPECT_EQ(p.keyframes[1].time_ms, 900u);
  ASSERT_EQ(p.keyframes[1].targets.size(), 2u);
  EXPECT_EQ(p.keyframes[1].targets[1].id, 6);
  EXPECT_EQ(p.keyframes[1].targets[1].position, 1000);
  const std::vector<std::string> m = messages(out);
  ASSERT_EQ(m.size(), 2u);
  EXPECT_EQ(m[1],
            "13:11 warning: 'base' has no known position before this move, and other tracks' "
            "actions cut it: it holds until 0.2 s and reaches 1000 in 0.9 s (the action that "
            "ends the move), not in 1.1 s; from 0 it needs 1 s at max_speed 1000/s; give it a "
            "position before this, or start its move with the others");
}

// A first move longer than one action (30 s) would be split, and its first part would carry
// the end: base would arrive at 22.5 s of a 45 s move. It is an error, located.
TEST(MotionChecks, AFirstMoveLongerThanOneActionIsAnError) {
  const auto out = compile_text("robot: xarm\nsequence:\n  - move: {base: 1000}\n    time: 45s\n");
  EXPECT_EQ(messages(out),
            std::vector<std::string>{
                "3:5 error: 'base' has no known position before this move, so it cannot be split "
                "into actions (45000ms is longer than the controller's 30s per action); move it "
                "to an absolute position first"});
  // After a move that gives it a position, the same 45 s move is two actions of 22.5 s, the
  // first to the midpoint: 500 + (1000 - 500) / 2 = 750.
  const auto ok = compile_text(
      "robot: xarm\nsequence:\n  - move: {base: 500}\n    time: 1s\n  - move: {base: 1000}\n"
      "    time: 45s\n");
  const ServoProgram& p = program_of(ok);
  ASSERT_EQ(p.keyframes.size(), 3u);
  EXPECT_EQ(p.keyframes[1].time_ms, 22500u);
  EXPECT_EQ(p.keyframes[1].targets[0].position, 750);
}

TEST(MotionChecks, TheFirstMoveOfSeveralServosIsOneWarningNamingTheSlowest) {
  // The xArm's servos (0..1000) default to 375deg/s, 1562.5 units/s (printed 1562/s). elbow to
  // 900 may come from 0: 900 units, 0.576 s, named 0.58 s; claw and base to 500: 0.32 s;
  // wrist_roll to 700: 700 units, 0.448 s. All four are slower than 300ms; the warning names
  // the slowest.
  const auto out = compile_text(R"(robot: xarm
sequence:
  - move: {elbow: 900, claw: 500, base: 500, wrist_roll: 700}
    time: 300ms
)");
  EXPECT_EQ(messages(out),
            std::vector<std::string>{
                "3:5 warning: first move of servos 'claw', 'wrist_roll', 'elbow', 'base' may start "
                "anywhere in their limits; the slowest, 'elbow' (0..1000): from 0 it needs 0.58 s "
                "at max_speed 1562/s; this move takes 0.3 s"});
  // At 320ms only elbow and wrist_roll are too fast.
  const auto slower = compile_text(R"(robot: xarm
sequence:
  - move: {elbow: 900, claw: 500, base: 500, wrist_roll: 700}
    time: 320ms
)");
  EXPECT_EQ(messages(slower),
            std::vector<std::string>{
                "3:5 warning: first move of servos 'wrist_roll', 'elbow' may start anywhere in "
                "their limits; the slowest, 'elbow' (0..1000): from 0 it needs 0.58 s at "
                "max_speed 1562/s; this move takes 0.32 s"});
}

TEST(MotionChecks, ServosBreakingALimitAlikeShareOneWarning) {
  // A mirrored pair each moving 300 units in 200ms: 1500/s, above both 1000/s limits; odd moves
  // as far but may go 2000/s.
  const auto out = compile_text(R"(robot:
  profile: lsc-16
  servos:
    left: {id: 0, max_speed: 1000/s}
    right: {id: 1, max_speed: 1000/s}
    odd: {id: 2, max_speed: 2000/s}
sequence:
  - move: {left: 1500, right: 1500, odd: 1500}
    time: 2s
  - move: {left: 1800, right: 1200, odd: 1800}
    time: 200ms
  - move: {left: 1500, right: 1500}
    time: 200ms
    ease: quad-in-out
    tolerance: 2
)");
  // The eased move peaks at twice the average, 3000/s, in both servos.
  EXPECT_EQ(messages(out),
            (std::vector<std::string>{
                "10:5 warning: servos 'left', 'right' move 300 in 200ms at 1500/s, above their "
                "1000/s",
                "12:5 warning: servos 'left', 'right' move 300 in 200ms and peak at 3000/s on "
                "this quad-in-out curve, above their 1000/s"}));
}

TEST(MotionChecks, ACurveTheActionsCannotFollowIsOneWarningForAllItsServos) {
  // 300 units of quad-in-out in 200ms: ten 20ms actions cannot keep within 1 unit of the curve
  // (a chord across its fastest part sags by more), in either servo, at several instants.
  const auto out = compile_text(R"(robot:
  profile: lsc-16
sequence:
  - move: {ch0: 1500, ch1: 1500}
    time: 2s
  - move: {ch0: 1800, ch1: 1200}
    time: 200ms
    ease: quad-in-out
)");
  std::vector<std::string> fit;
  for (const std::string& m : messages(out)) {
    if (m.find("cannot keep") != std::string::npos) fit.push_back(m);
  }
  ASSERT_EQ(fit.size(), 1u) << diagnostics_of(out);
  const std::string head =
      "6:5 warning: even 20ms actions cannot keep servos 'ch0', 'ch1' within 1 of this curve: "
      "up to ";
  EXPECT_EQ(fit[0].substr(0, head.size()), head);
}

TEST(MotionChecks, AWarningInsideASectionNamesItsPerformance) {
  const auto out = compile_text(R"(robot:
  profile: xarm
  servos:
    base: {max_speed: 1000/s}
sections:
  swing:
    - move: {base: +300}
      time: 200ms
sequence:
  - move: {base: 200}
    time: 1s
  - section: swing
  - move: {base: 500}
    time: 1s
  - section: swing
)");
  // Both performances move 300 in 200ms: one warning (the same fact), noted at the first
  // performance; the second adds nothing.
  EXPECT_EQ(messages(out), (std::vector<std::string>{
                               "7:7 warning: 300 in 200ms is 1500/s, above base's 1000/s",
                               "12:14 note: in section 'swing', performed here",
                           }));
}

TEST(MotionChecks, UnknownRobotsAndEasingsListTheValidNames) {
  EXPECT_EQ(messages(compile_text("robot: r2d2\nsequence: []\n")),
            std::vector<std::string>{"1:8 error: unknown robot 'r2d2' (robots: xarm, bus, lsc-16, "
                                     "lsc-32, lsc-6, learm, raspblock)"});
  EXPECT_EQ(
      messages(compile_text("robot: xarn\nsequence: []\n")),
      std::vector<std::string>{"1:8 error: unknown robot 'xarn'; did you mean 'xarm'? "
                               "(robots: xarm, bus, lsc-16, lsc-32, lsc-6, learm, raspblock)"});
  const std::string easings =
      "(easings: linear, in, out, in-out; back, bounce, circ, cubic, elastic, expo, quad, quart, "
      "quint, sine, each with -in, -out or -in-out; cubic-bezier(x1, y1, x2, y2))";
  const std::string move =
      "robot: xarm\nsequence:\n  - move: {base: 500}\n    time: 1s\n"
      "  - move: {base: 600}\n    time: 1s\n    ease: ";
  EXPECT_EQ(messages(compile_text(move + "wobbly\n")),
            std::vector<std::string>{"7:11 error: unknown easing 'wobbly' " + easings});
  EXPECT_EQ(messages(compile_text(move + "bounce-ot\n")),
            std::vector<std::string>{"7:11 error: unknown easing 'bounce-ot'; did you mean "
                                     "'bounce-out'? " +
                                     easings});
}

TEST(MotionChecks, AShowFileGivenToOneRobotsFrontEndSaysItIsAShow) {
  const auto out = compile_text(R"(show: duet
performers:
  - file: a.yaml
    port: emu:xarm
)");
  EXPECT_FALSE(out.program);
  EXPECT_EQ(messages(out), (std::vector<std::string>{
                               "2:1 error: this is a show file (it has 'performers'), not one "
                               "robot's choreography",
                               "2:1 note: a show runs with 'seqc show main.yaml'",
                           }));
}

}  // namespace
}  // namespace seqc::compiler

namespace seqc::compiler {
namespace {

// docs/language.md's worked number: 100 units of circ-in over 1 s at tolerance 1. The gentlest
// motion within 1 unit of the curve that still ends at 100 leaves the end along the tangent to
// the band's lower edge 100 sqrt(1 - u^2) ... : with v = 1 - u, (100 sqrt(v (2 - v)) - 1) / v
// is largest at v = 2/10001, where it is (20000/10001 - 1) / (2/10001) = 9999/2 = 4999.5/s.
TEST(VerticalCurves, AreJudgedByTheLeastSpeedWithinTheirTolerance) {
  auto text = [](const char* max_speed, const char* ease) {
    return std::string("robot:\n  profile: xarm\n  servos:\n    base: {max_speed: ") + max_speed +
           "}\nsequence:\n  - move: {base: 400}\n    time: 2s\n  - move: {base: 500}\n"
           "    time: 1s\n    ease: " +
           ease + "\n";
  };
  auto speed_messages = [](const CompileOutput& out) {
    std::vector<std::string> found;
    for (const std::string& m : testing::messages(out)) {
      if (m.find("/s") != std::string::npos) found.push_back(m);
    }
    return found;
  };
  for (const char* ease : {"circ-in", "circ-out"}) {
    EXPECT_EQ(speed_messages(testing::compile_text(text("4999/s", ease), true)),
              (std::vector<std::string>{
                  std::string("8:5 warning: 100 in 1000ms needs at least 4999.5/s on this ") +
                  ease + " curve within a tolerance of 1, above base's 4999/s"}))
        << ease;
    EXPECT_EQ(speed_messages(testing::compile_text(text("5000/s", ease), true)),
              std::vector<std::string>{})
        << ease;
  }
}

// 100 units of circ-in in 2 s at tolerance 5 (the golden bad-easing-true-peak.yaml's, clean
// under its 800/s) needs (100^2 - 5^2) / (2 x 5 x 2 s) = 9975 / 20 = 498.75/s. (--strict makes
// such a warning an error where the CLI reports it.)
TEST(VerticalCurves, AWiderToleranceNeedsLessSpeed) {
  auto out = testing::compile_text(
      "robot:\n  profile: xarm\n  servos:\n    base: {max_speed: 498/s}\nsequence:\n"
      "  - move: {base: 450}\n    time: 2s\n  - move: {base: 550}\n    time: 2s\n"
      "    ease: circ-in\n    tolerance: 5\n",
      true);
  EXPECT_EQ(
      testing::messages(out),
      (std::vector<std::string>{"8:5 warning: 100 in 2000ms needs at least 498.75/s on this "
                                "circ-in curve within a tolerance of 5, above base's 498/s"}));
}

}  // namespace
}  // namespace seqc::compiler
