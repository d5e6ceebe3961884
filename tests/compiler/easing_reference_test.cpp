// Every easing name, parsed as a file would write it, against the textbook formula written in
// tests/compiler/easing_reference.hpp, at points on both halves of each in-out curve and on
// every arc of the bounces; cubic-bezier against a bisection solver and against values worked
// out by hand for CSS's named curves.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <set>
#include <string>

#include "compiler/timeline/easing.hpp"
#include "tests/compiler/easing_reference.hpp"

namespace seqc::compiler {
namespace {

namespace ref = testing::ease_ref;

// Both halves of the in-out curves (0.1, 0.25, 0.4 | 0.6, 0.75, 0.9) and all four arcs of
// bounce-out, also as bounce-in-out maps them (1 - 2t and 2t - 1 land on each arc).
constexpr double kPoints[] = {0,    0.02, 0.05, 0.1,  0.2, 0.25, 0.3,  0.4,  0.45, 0.5,
                              0.55, 0.6,  0.7,  0.75, 0.8, 0.9,  0.95, 0.98, 1};

Easing parsed(const std::string& name) {
  const EaseParse p = parse_easing(name);
  EXPECT_TRUE(p.easing.has_value()) << name << ": " << p.message;
  return p.easing.value_or(Easing{});
}

TEST(EasingReference, EveryNameMatchesItsTextbookFormula) {
  for (const auto& [name, formula] : ref::by_name()) {
    const Easing e = parsed(name);
    for (double t : kPoints) {
      EXPECT_NEAR(e.at(t), formula(t), 1e-9) << name << " at t = " << t;
    }
  }
}

TEST(EasingReference, EverySlopeIsTheReferenceCurvesDerivative) {
  // A central difference of the reference, h = 1e-6, at points inside (0, 1) away from the
  // bounces' landings (where the slope jumps); at the ends, one-sided differences that stay
  // inside [0, 1].
  constexpr double h = 1e-6;
  for (const auto& [name, formula] : ref::by_name()) {
    const Easing e = parsed(name);
    for (double t : kPoints) {
      double expected = 0;
      if (t == 0) {
        expected = (formula(h) - formula(0)) / h;
      } else if (t == 1) {
        expected = (formula(1) - formula(1 - h)) / h;
      } else {
        expected = (formula(t + h) - formula(t - h)) / (2 * h);
      }
      if (name.rfind("circ", 0) == 0 && std::isinf(e.slope(t))) {
        // circ is vertical where its -in half ends: the difference there only grows with 1/h.
        EXPECT_GT(expected, 100) << name << " at t = " << t;
        continue;
      }
      EXPECT_NEAR(e.slope(t), expected, 1e-4 * std::max(1.0, std::abs(expected)))
          << name << " at t = " << t;
    }
  }
}

TEST(EasingReference, EveryCurveStartsAndEndsWithoutAJump) {
  // The values next to the ends are as close to 0 and 1 as the slope there allows: a curve
  // snapped to 0 at t = 0 (the textbook expo-in starts at 2^-10) fails this.
  for (const std::string& name : easing_names()) {
    const Easing e = parsed(name);
    const double near0 = e.at(1e-9), near1 = e.at(1 - 1e-9);
    EXPECT_LT(std::abs(near0), 1e-9 * (std::abs(e.slope(0)) + 1)) << name;
    if (!std::isinf(e.slope(1))) {
      EXPECT_LT(std::abs(1 - near1), 1e-9 * (std::abs(e.slope(1)) + 1)) << name;
    }
  }
}

TEST(EasingReference, TheNameListIsTheDocumentedOne) {
  // linear, the three quadratic shorthands and ten families in three modes.
  const std::vector<std::string>& names = easing_names();
  EXPECT_EQ(names.size(), 4u + 10u * 3u);
  const std::set<std::string> unique(names.begin(), names.end());
  EXPECT_EQ(unique.size(), names.size());
  for (const std::string& n : names) EXPECT_TRUE(ref::by_name().count(n)) << n;
  // A family's canonical name reads back as written.
  for (const std::string& n : names) {
    if (n == "in" || n == "out" || n == "in-out") continue;
    EXPECT_EQ(parsed(n).name(), n);
  }
  EXPECT_EQ(parsed("in-out").name(), "quad-in-out");
  EXPECT_EQ(parsed("ease-in").name(), "quad-in");
}

TEST(EasingReference, InOutConstantsAtHandPickedPoints) {
  // Values worked out from the formulas with the constants written out, on both halves.
  // back-in-out at 0.25: (0.5)^2 * ((c2 + 1) * 0.5 - c2) / 2 with c2 = 1.70158 * 1.525.
  const double c2 = 1.70158 * 1.525;
  EXPECT_NEAR(parsed("back-in-out").at(0.25), 0.25 * (0.5 * (c2 + 1) - c2) / 2, 1e-12);
  // ... and at 0.75 by the curve's point symmetry about (0.5, 0.5).
  EXPECT_NEAR(parsed("back-in-out").at(0.75), 1 - 0.25 * (0.5 * (c2 + 1) - c2) / 2, 1e-12);
  // elastic-in-out at 0.25: -(2^-5 * sin((5 - 11.125) * 2pi/4.5)) / 2, rescaled by its start
  // h0 = 2^-11 sin(pi/18) to (v - h0) / (1 - 2 h0).
  const double c5 = 2 * std::numbers::pi / 4.5;
  const double h0 = std::sin(std::numbers::pi / 18) / 2048;
  EXPECT_NEAR(parsed("elastic-in-out").at(0.25),
              (-(std::pow(2, -5) * std::sin(-6.125 * c5)) / 2 - h0) / (1 - 2 * h0), 1e-12);
  EXPECT_NEAR(parsed("elastic-in-out").at(0.75),
              (std::pow(2, -5) * std::sin(3.875 * c5) / 2 + 1 - h0) / (1 - 2 * h0), 1e-12);
  // bounce-out at 0.5 lies on the second arc: 7.5625 * (0.5 - 1.5/2.75)^2 + 0.75.
  EXPECT_NEAR(parsed("bounce-out").at(0.5), 7.5625 * std::pow(0.5 - 1.5 / 2.75, 2) + 0.75, 1e-12);
  // Exact values: quad-in-out at 0.25 is 2/16; expo-in at 0.5 is (2^5 - 1) / 1023 = 31/1023;
  // sine-in-out at 1/2.
  EXPECT_DOUBLE_EQ(parsed("in-out").at(0.25), 0.125);
  EXPECT_NEAR(parsed("expo-in").at(0.5), 31.0 / 1023, 1e-15);
  EXPECT_NEAR(parsed("sine-in-out").at(0.5), 0.5, 1e-15);
  EXPECT_NEAR(parsed("circ-in").at(0.6), 0.2, 1e-15);  // 1 - sqrt(1 - 0.36)
}

TEST(EasingReference, CubicBezierMatchesABisectionSolver) {
  struct Curve {
    double x1, y1, x2, y2;
    const char* text;
  };
  const Curve curves[] = {
      {0.25, 0.1, 0.25, 1, "cubic-bezier(0.25, 0.1, 0.25, 1)"},              // CSS ease
      {0.42, 0, 1, 1, "cubic-bezier(0.42, 0, 1, 1)"},                        // CSS ease-in
      {0, 0, 0.58, 1, "cubic-bezier(0, 0, 0.58, 1)"},                        // CSS ease-out
      {0.42, 0, 0.58, 1, "cubic-bezier(0.42,0,0.58,1)"},                     // CSS ease-in-out
      {0.68, -0.55, 0.265, 1.55, "cubic-bezier(0.68, -0.55, 0.265, 1.55)"},  // overshoots
      {0.1, 0.9, 0.2, 1, "cubic-bezier(0.1, 0.9, 0.2, 1)"},
      // x'(s) = 3(1 - 2s)^2 vanishes at s = 1/2: Newton's method stalls there.
      {1, 0, 0, 1, "cubic-bezier(1, 0, 0, 1)"},
  };
  for (const Curve& c : curves) {
    const Easing e = parsed(c.text);
    EXPECT_EQ(e.family, EaseFamily::Bezier) << c.text;
    for (double t : kPoints) {
      // Where x'(s) = 0 the value is ill-conditioned (near t = 1/2 for (1, 0, 0, 1): a
      // rounding of 1e-16 in x moves s by 1e-6), so no double solver pins it to 1e-9.
      if (c.x1 == 1 && std::abs(t - 0.5) < 0.1) continue;
      EXPECT_NEAR(e.at(t), ref::bezier(c.x1, c.y1, c.x2, c.y2, t), 1e-9) << c.text << " at " << t;
    }
  }
  // ... there its value follows from the curve's point symmetry about (0.5, 0.5).
  EXPECT_NEAR(parsed("cubic-bezier(1, 0, 0, 1)").at(0.5), 0.5, 1e-12);
}

// CSS `ease` in closed form: x(s) = s^3 - 0.75 s^2 + 0.75 s and y(s) = 0.3 s + 2.4 s^2 - 1.7 s^3
// (expanding the Bernstein form with (0.25, 0.1), (0.25, 1)); x(s) = t has one real root, found
// by Cardano's formula.
double css_ease(double t) {
  const double a = -0.75, b = 0.75, c = -t;
  const double p = b - a * a / 3;
  const double q = 2 * a * a * a / 27 - a * b / 3 + c;
  const double d = std::sqrt(q * q / 4 + p * p * p / 27);
  const double s = std::cbrt(-q / 2 + d) + std::cbrt(-q / 2 - d) - a / 3;
  return 0.3 * s + 2.4 * s * s - 1.7 * s * s * s;
}

TEST(EasingReference, CssNamedCurvesHaveTheirKnownValues) {
  const Easing ease = parsed("cubic-bezier(0.25, 0.1, 0.25, 1)");
  for (double t : kPoints) EXPECT_NEAR(ease.at(t), css_ease(t), 1e-9) << t;
  EXPECT_NEAR(ease.at(0.5), 0.8024033875848, 1e-12);
  // ease-in-out is point-symmetric about (0.5, 0.5); ease-out mirrors ease-in.
  const Easing in_out = parsed("cubic-bezier(0.42, 0, 0.58, 1)");
  const Easing in = parsed("cubic-bezier(0.42, 0, 1, 1)");
  const Easing out = parsed("cubic-bezier(0, 0, 0.58, 1)");
  EXPECT_NEAR(in_out.at(0.5), 0.5, 1e-12);
  for (double t : kPoints) {
    EXPECT_NEAR(in_out.at(t) + in_out.at(1 - t), 1, 1e-9) << t;
    EXPECT_NEAR(in.at(t) + out.at(1 - t), 1, 1e-9) << t;
  }
  // Control points on the diagonal make the identity.
  const Easing diagonal = parsed("cubic-bezier(0.3, 0.3, 0.8, 0.8)");
  for (double t : kPoints) EXPECT_NEAR(diagonal.at(t), t, 1e-9) << t;
}

}  // namespace
}  // namespace seqc::compiler
