// Reference easing curves for the tests, written from the textbook formulas (the ones published
// at easings.net and used by CSS and the animation libraries; expo and elastic rescaled to
// start at exactly 0, as docs/language.md gives them), each family and mode in its own
// closed form, so that a test comparing compiler/timeline/easing.cpp with these shares no code
// or structure with it. cubic-bezier is solved by plain bisection on x(s) = t.
//
// by_name() pairs every easing name of docs/language.md with its formula, independently of the
// compiler's name table; at() evaluates a parsed Easing by its family and mode (for tests whose
// subject is not the name table).
#pragma once

#include <cmath>
#include <functional>
#include <map>
#include <numbers>
#include <string>

#include "compiler/timeline/easing.hpp"

namespace seqc::compiler::testing::ease_ref {

inline constexpr double kPi = std::numbers::pi;
inline constexpr double kC1 = 1.70158;      // back
inline constexpr double kC2 = kC1 * 1.525;  // back-in-out
inline constexpr double kC3 = kC1 + 1;
inline constexpr double kC4 = 2 * kPi / 3;    // elastic
inline constexpr double kC5 = 2 * kPi / 4.5;  // elastic-in-out

inline double quad_in(double t) { return t * t; }
inline double quad_out(double t) { return 1 - (1 - t) * (1 - t); }
inline double quad_in_out(double t) {
  return t < 0.5 ? 2 * t * t : 1 - std::pow(-2 * t + 2, 2) / 2;
}

inline double cubic_in(double t) { return t * t * t; }
inline double cubic_out(double t) { return 1 - std::pow(1 - t, 3); }
inline double cubic_in_out(double t) {
  return t < 0.5 ? 4 * t * t * t : 1 - std::pow(-2 * t + 2, 3) / 2;
}

inline double quart_in(double t) { return t * t * t * t; }
inline double quart_out(double t) { return 1 - std::pow(1 - t, 4); }
inline double quart_in_out(double t) {
  return t < 0.5 ? 8 * t * t * t * t : 1 - std::pow(-2 * t + 2, 4) / 2;
}

inline double quint_in(double t) { return t * t * t * t * t; }
inline double quint_out(double t) { return 1 - std::pow(1 - t, 5); }
inline double quint_in_out(double t) {
  return t < 0.5 ? 16 * t * t * t * t * t : 1 - std::pow(-2 * t + 2, 5) / 2;
}

inline double sine_in(double t) { return 1 - std::cos(t * kPi / 2); }
inline double sine_out(double t) { return std::sin(t * kPi / 2); }
inline double sine_in_out(double t) { return -(std::cos(kPi * t) - 1) / 2; }

// expo, exactly 0 and 1 at its ends: the textbook 2^(10t - 10) starts at 2^-10, so it is
// rescaled, (2^(10t - 10) - 2^-10) / (1 - 2^-10), which is (2^(10t) - 1) / 1023.
inline double expo_in(double t) { return (std::pow(2, 10 * t) - 1) / 1023; }
inline double expo_out(double t) { return (1024 - std::pow(2, 10 - 10 * t)) / 1023; }
inline double expo_in_out(double t) {
  return t < 0.5 ? (std::pow(2, 20 * t) - 1) / 2046 : 1 - (std::pow(2, 20 - 20 * t) - 1) / 2046;
}

inline double circ_in(double t) { return 1 - std::sqrt(1 - t * t); }
inline double circ_out(double t) { return std::sqrt(1 - (t - 1) * (t - 1)); }
inline double circ_in_out(double t) {
  return t < 0.5 ? (1 - std::sqrt(1 - (2 * t) * (2 * t))) / 2
                 : (std::sqrt(1 - (-2 * t + 2) * (-2 * t + 2)) + 1) / 2;
}

inline double back_in(double t) { return kC3 * t * t * t - kC1 * t * t; }
inline double back_out(double t) { return 1 + kC3 * std::pow(t - 1, 3) + kC1 * std::pow(t - 1, 2); }
inline double back_in_out(double t) {
  return t < 0.5 ? (std::pow(2 * t, 2) * ((kC2 + 1) * 2 * t - kC2)) / 2
                 : (std::pow(2 * t - 2, 2) * ((kC2 + 1) * (t * 2 - 2) + kC2) + 2) / 2;
}

// elastic, rescaled like expo: the textbook -in curve starts at -2^-10 sin(-10.75 * 2pi/3) =
// -2^-11 and ends at 1, so -in is (textbook + 2^-11) / (1 + 2^-11) and -out, its mirror,
// (textbook-out + 0) / (1 + 2^-11). The textbook in-out starts at h0 = 2^-11 sin(pi/18)
// (-(2^-10 sin(-11.125 * 2pi/4.5)) / 2, and -11.125/4.5 turns is 190 degrees) and is 1/2 at
// t = 1/2, so each half is (textbook - h0) / (1 - 2 h0).
inline constexpr double kElasticStart = 1.0 / 2048;  // 2^-11
inline const double kElasticInOutStart = std::sin(kPi / 18) / 2048;
inline double elastic_in(double t) {
  return (-std::pow(2, 10 * t - 10) * std::sin((t * 10 - 10.75) * kC4) + kElasticStart) /
         (1 + kElasticStart);
}
inline double elastic_out(double t) {
  return (std::pow(2, -10 * t) * std::sin((t * 10 - 0.75) * kC4) + 1) / (1 + kElasticStart);
}
inline double elastic_in_out(double t) {
  const double h0 = kElasticInOutStart;
  const double textbook =
      t < 0.5 ? -(std::pow(2, 20 * t - 10) * std::sin((20 * t - 11.125) * kC5)) / 2
              : (std::pow(2, -20 * t + 10) * std::sin((20 * t - 11.125) * kC5)) / 2 + 1;
  return (textbook - h0) / (1 - 2 * h0);
}

// Four parabolic arcs meeting at the bounces 1/d1, 2/d1 and 2.5/d1.
inline double bounce_out(double t) {
  constexpr double n1 = 7.5625;
  constexpr double d1 = 2.75;
  if (t < 1 / d1) return n1 * t * t;
  if (t < 2 / d1) return n1 * (t - 1.5 / d1) * (t - 1.5 / d1) + 0.75;
  if (t < 2.5 / d1) return n1 * (t - 2.25 / d1) * (t - 2.25 / d1) + 0.9375;
  return n1 * (t - 2.625 / d1) * (t - 2.625 / d1) + 0.984375;
}
inline double bounce_in(double t) { return 1 - bounce_out(1 - t); }
inline double bounce_in_out(double t) {
  return t < 0.5 ? (1 - bounce_out(1 - 2 * t)) / 2 : (1 + bounce_out(2 * t - 1)) / 2;
}

// CSS cubic-bezier(x1, y1, x2, y2): the Bezier curve from (0, 0) to (1, 1) with control points
// (x1, y1) and (x2, y2), read as y at the parameter s where x(s) = t. x is non-decreasing in s
// for x1, x2 in [0, 1], so bisection on s finds that parameter; 200 halvings reach the limit of
// double precision.
inline double bezier(double x1, double y1, double x2, double y2, double t) {
  const auto b = [](double p1, double p2, double s) {
    return 3 * (1 - s) * (1 - s) * s * p1 + 3 * (1 - s) * s * s * p2 + s * s * s;
  };
  double lo = 0, hi = 1;
  for (int i = 0; i < 200 && lo < hi; ++i) {
    const double mid = (lo + hi) / 2;
    if (mid <= lo || mid >= hi) break;
    (b(x1, x2, mid) < t ? lo : hi) = mid;
  }
  return b(y1, y2, (lo + hi) / 2);
}

// Every name of docs/language.md ("Easing"), shorthands included, with its formula.
inline const std::map<std::string, std::function<double(double)>>& by_name() {
  static const std::map<std::string, std::function<double(double)>> m = {
      {"linear", [](double t) { return t; }},
      {"in", quad_in},
      {"out", quad_out},
      {"in-out", quad_in_out},
      {"ease-in", quad_in},
      {"ease-out", quad_out},
      {"ease-in-out", quad_in_out},
      {"quad-in", quad_in},
      {"quad-out", quad_out},
      {"quad-in-out", quad_in_out},
      {"cubic-in", cubic_in},
      {"cubic-out", cubic_out},
      {"cubic-in-out", cubic_in_out},
      {"quart-in", quart_in},
      {"quart-out", quart_out},
      {"quart-in-out", quart_in_out},
      {"quint-in", quint_in},
      {"quint-out", quint_out},
      {"quint-in-out", quint_in_out},
      {"sine-in", sine_in},
      {"sine-out", sine_out},
      {"sine-in-out", sine_in_out},
      {"expo-in", expo_in},
      {"expo-out", expo_out},
      {"expo-in-out", expo_in_out},
      {"circ-in", circ_in},
      {"circ-out", circ_out},
      {"circ-in-out", circ_in_out},
      {"back-in", back_in},
      {"back-out", back_out},
      {"back-in-out", back_in_out},
      {"elastic-in", elastic_in},
      {"elastic-out", elastic_out},
      {"elastic-in-out", elastic_in_out},
      {"bounce-in", bounce_in},
      {"bounce-out", bounce_out},
      {"bounce-in-out", bounce_in_out},
  };
  return m;
}

// The reference value of a parsed easing at t in [0, 1], by its family and mode.
inline double at(const Easing& e, double t) {
  if (e.family == EaseFamily::Bezier) {
    if (t <= 0) return 0;
    if (t >= 1) return 1;
    return bezier(e.x1, e.y1, e.x2, e.y2, t);
  }
  using F = double (*)(double);
  struct Modes {
    F in, out, in_out;
  };
  static const std::map<EaseFamily, Modes> table = {
      {EaseFamily::Quad, {quad_in, quad_out, quad_in_out}},
      {EaseFamily::Cubic, {cubic_in, cubic_out, cubic_in_out}},
      {EaseFamily::Quart, {quart_in, quart_out, quart_in_out}},
      {EaseFamily::Quint, {quint_in, quint_out, quint_in_out}},
      {EaseFamily::Sine, {sine_in, sine_out, sine_in_out}},
      {EaseFamily::Expo, {expo_in, expo_out, expo_in_out}},
      {EaseFamily::Circ, {circ_in, circ_out, circ_in_out}},
      {EaseFamily::Back, {back_in, back_out, back_in_out}},
      {EaseFamily::Elastic, {elastic_in, elastic_out, elastic_in_out}},
      {EaseFamily::Bounce, {bounce_in, bounce_out, bounce_in_out}},
  };
  const auto it = table.find(e.family);
  if (it == table.end()) return t;  // linear
  const Modes& m = it->second;
  return e.mode == EaseMode::In ? m.in(t) : e.mode == EaseMode::Out ? m.out(t) : m.in_out(t);
}

}  // namespace seqc::compiler::testing::ease_ref
