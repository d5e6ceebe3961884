// The textbook easing formulas (the ones animation libraries and CSS share); each family's
// -in curve f gives -out as 1 - f(1 - t) and -in-out as f(2t)/2, then 1 - f(2 - 2t)/2 (back
// and elastic in-out use their own constants). expo and elastic are rescaled to start at
// exactly 0 (see in_curve). Every curve also has its exact derivative, so speed checks read the
// true peak rather than a difference that may straddle an end.
#include "compiler/timeline/easing.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <numbers>

namespace seqc::compiler {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kBack = 1.70158;             // overshoot of about 10 %
constexpr double kBackInOut = kBack * 1.525;  // the in-out variant's larger constant

// bounce's parabolas: n t^2 and its copies shifted to the landings at 1/d, 2/d and 2.5/d.
constexpr double kBounceN = 7.5625;
constexpr double kBounceD = 2.75;

double bounce_out(double t) {
  constexpr double n = kBounceN;
  constexpr double d = kBounceD;
  if (t < 1 / d) return n * t * t;
  if (t < 2 / d) {
    t -= 1.5 / d;
    return n * t * t + 0.75;
  }
  if (t < 2.5 / d) {
    t -= 2.25 / d;
    return n * t * t + 0.9375;
  }
  t -= 2.625 / d;
  return n * t * t + 0.984375;
}

// The slope of each parabola where t lies (at a landing, the arc that ends there).
double bounce_out_slope(double t) {
  constexpr double n = kBounceN;
  constexpr double d = kBounceD;
  if (t <= 1 / d) return 2 * n * t;
  if (t <= 2 / d) return 2 * n * (t - 1.5 / d);
  if (t <= 2.5 / d) return 2 * n * (t - 2.25 / d);
  return 2 * n * (t - 2.625 / d);
}

// expo and elastic: the textbook curves start at 2^-10 (expo) or a fraction of it (elastic)
// and are then snapped to 0, a jump whose derivative is a spike. Each is rescaled instead,
// (g(t) - g(0)) / (g(1) - g(0)) with g(1) = 1, so it starts at 0 and ends at 1 with no jump.
constexpr double kExpoStart = 1.0 / 1024;  // 2^-10
constexpr double kLn2 = std::numbers::ln2;
// The elastic curve's phase: -2^(10t - 10) sin((10t - offset) c); -in uses c = 2pi/3 and
// offset 10.75, -in-out c = 2pi/4.5 and offset 11.125.
struct ElasticPhase {
  double c, offset;
};
constexpr ElasticPhase kElastic{2 * kPi / 3, 10.75};
constexpr ElasticPhase kElasticInOut{2 * kPi / 4.5, 11.125};
double elastic_raw(ElasticPhase p, double t) {
  return -std::pow(2, 10 * t - 10) * std::sin((10 * t - p.offset) * p.c);
}
double elastic_raw_slope(ElasticPhase p, double t) {
  const double angle = (10 * t - p.offset) * p.c;
  return -std::pow(2, 10 * t - 10) * 10 * (kLn2 * std::sin(angle) + p.c * std::cos(angle));
}
// g(0): -2^-10 sin(-10.75 * 2pi/3) = -2^-11 for -in; -2^-10 sin(-11.125 * 2pi/4.5) =
// 2^-10 sin(pi/18) for -in-out. Taken from the formula so the start is exactly 0.
double elastic_start(ElasticPhase p) { return elastic_raw(p, 0); }

// The -in curve of a family; -out and -in-out follow from it. `in_out`: back and elastic use
// their larger in-out constants.
double in_curve(EaseFamily f, bool in_out, double t) {
  switch (f) {
    case EaseFamily::Quad:
      return t * t;
    case EaseFamily::Cubic:
      return t * t * t;
    case EaseFamily::Quart:
      return t * t * t * t;
    case EaseFamily::Quint:
      return t * t * t * t * t;
    case EaseFamily::Sine:
      return 1 - std::cos(t * kPi / 2);
    case EaseFamily::Expo:
      return (std::pow(2, 10 * t - 10) - kExpoStart) / (1 - kExpoStart);
    case EaseFamily::Circ:
      return 1 - std::sqrt(std::max(0.0, 1 - t * t));
    case EaseFamily::Back: {
      const double c = in_out ? kBackInOut : kBack;
      return (c + 1) * t * t * t - c * t * t;
    }
    case EaseFamily::Elastic: {
      const ElasticPhase p = in_out ? kElasticInOut : kElastic;
      const double g0 = elastic_start(p);
      return (elastic_raw(p, t) - g0) / (1 - g0);
    }
    case EaseFamily::Bounce:
      return 1 - bounce_out(1 - t);
    default:
      return t;
  }
}

// d/dt of in_curve. Infinite where the curve is vertical (circ at t = 1).
double in_slope(EaseFamily f, bool in_out, double t) {
  switch (f) {
    case EaseFamily::Quad:
      return 2 * t;
    case EaseFamily::Cubic:
      return 3 * t * t;
    case EaseFamily::Quart:
      return 4 * t * t * t;
    case EaseFamily::Quint:
      return 5 * t * t * t * t;
    case EaseFamily::Sine:
      return kPi / 2 * std::sin(t * kPi / 2);
    case EaseFamily::Expo:
      return 10 * kLn2 * std::pow(2, 10 * t - 10) / (1 - kExpoStart);
    case EaseFamily::Circ: {
      const double r = 1 - t * t;
      return r <= 0 ? std::numeric_limits<double>::infinity() : t / std::sqrt(r);
    }
    case EaseFamily::Back: {
      const double c = in_out ? kBackInOut : kBack;
      return 3 * (c + 1) * t * t - 2 * c * t;
    }
    case EaseFamily::Elastic: {
      const ElasticPhase p = in_out ? kElasticInOut : kElastic;
      return elastic_raw_slope(p, t) / (1 - elastic_start(p));
    }
    case EaseFamily::Bounce:
      return bounce_out_slope(1 - t);
    default:
      return 1;
  }
}

// CSS cubic-bezier: the curve from (0,0) to (1,1) with control points (x1,y1), (x2,y2); the
// value at time t is y(s) where x(s) = t. x(s) is monotonic because x1, x2 are in [0, 1].
double bezier_coord(double p1, double p2, double s) {
  const double u = 1 - s;
  return 3 * u * u * s * p1 + 3 * u * s * s * p2 + s * s * s;
}
double bezier_coord_slope(double p1, double p2, double s) {
  const double u = 1 - s;
  return 3 * u * u * p1 + 6 * u * s * (p2 - p1) + 3 * s * s * (1 - p2);
}

// The parameter s where x(s) = t.
double bezier_parameter(const Easing& e, double t) {
  double s = t;
  for (int i = 0; i < 8; ++i) {  // Newton, then bisection if it stalls
    const double dx = bezier_coord(e.x1, e.x2, s) - t;
    if (std::abs(dx) < 1e-12) return s;
    const double d = bezier_coord_slope(e.x1, e.x2, s);
    if (std::abs(d) < 1e-9) break;
    s -= dx / d;
    if (s < 0 || s > 1) break;
  }
  double lo = 0, hi = 1;
  s = t;
  for (int i = 0; i < 60; ++i) {
    const double x = bezier_coord(e.x1, e.x2, s);
    if (std::abs(x - t) < 1e-12) break;
    (x < t ? lo : hi) = s;
    s = (lo + hi) / 2;
  }
  return s;
}

double bezier(const Easing& e, double t) {
  return bezier_coord(e.y1, e.y2, bezier_parameter(e, t));
}

// dy/dx = y'(s) / x'(s); infinite where x'(s) = 0 and y'(s) is not (a vertical tangent). Where
// both vanish (an end whose control point sits on it) the limit is taken just inside.
double bezier_slope(const Easing& e, double t) {
  double s = bezier_parameter(e, t);
  double dx = bezier_coord_slope(e.x1, e.x2, s);
  double dy = bezier_coord_slope(e.y1, e.y2, s);
  if (std::abs(dx) < 1e-12 && std::abs(dy) < 1e-12) {
    s = std::clamp(s, 1e-6, 1 - 1e-6);
    dx = bezier_coord_slope(e.x1, e.x2, s);
    dy = bezier_coord_slope(e.y1, e.y2, s);
  }
  if (dx <= 0) return dy == 0 ? 0 : std::copysign(std::numeric_limits<double>::infinity(), dy);
  return dy / dx;
}

const std::map<std::string, EaseFamily, std::less<>>& families() {
  static const std::map<std::string, EaseFamily, std::less<>> f = {
      {"quad", EaseFamily::Quad},    {"cubic", EaseFamily::Cubic}, {"quart", EaseFamily::Quart},
      {"quint", EaseFamily::Quint},  {"sine", EaseFamily::Sine},   {"expo", EaseFamily::Expo},
      {"circ", EaseFamily::Circ},    {"back", EaseFamily::Back},   {"elastic", EaseFamily::Elastic},
      {"bounce", EaseFamily::Bounce}};
  return f;
}

std::string trim(std::string_view s) {
  while (!s.empty() && s.front() == ' ') s.remove_prefix(1);
  while (!s.empty() && s.back() == ' ') s.remove_suffix(1);
  return std::string(s);
}

std::string number_text(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

EaseParse parse_bezier(std::string_view args) {
  double v[4];
  static constexpr const char* kNames[] = {"x1", "y1", "x2", "y2"};
  std::size_t at = 0;
  for (int i = 0; i < 4; ++i) {
    const std::size_t comma = i < 3 ? args.find(',', at) : args.size();
    if (comma == std::string_view::npos) {
      return {std::nullopt, "cubic-bezier needs four numbers: cubic-bezier(x1, y1, x2, y2)"};
    }
    const std::string part = trim(args.substr(at, comma - at));
    const char* end = part.data() + part.size();
    auto [p, ec] = std::from_chars(part.data(), end, v[i]);
    if (part.empty() || ec != std::errc() || p != end || !std::isfinite(v[i])) {
      return {std::nullopt,
              std::string("cubic-bezier's ") + kNames[i] + " '" + part + "' is not a number"};
    }
    at = comma + 1;
  }
  for (int i : {0, 2}) {
    if (v[i] < 0 || v[i] > 1) {
      return {std::nullopt, std::string("cubic-bezier's ") + kNames[i] + " is " +
                                number_text(v[i]) + "; x values must lie in [0, 1]"};
    }
  }
  Easing e;
  e.family = EaseFamily::Bezier;
  e.x1 = v[0];
  e.y1 = v[1];
  e.x2 = v[2];
  e.y2 = v[3];
  return {e, {}};
}

}  // namespace

double Easing::at(double t) const {
  if (t <= 0) return 0;
  if (t >= 1) return 1;
  switch (family) {
    case EaseFamily::Linear:
      return t;
    case EaseFamily::Bezier:
      return bezier(*this, t);
    default:
      break;
  }
  const bool in_out = mode == EaseMode::InOut;
  switch (mode) {
    case EaseMode::In:
      return in_curve(family, in_out, t);
    case EaseMode::Out:
      return 1 - in_curve(family, in_out, 1 - t);
    case EaseMode::InOut:
      return t < 0.5 ? in_curve(family, in_out, 2 * t) / 2
                     : 1 - in_curve(family, in_out, 2 - 2 * t) / 2;
  }
  return t;
}

double Easing::slope(double t) const {
  t = std::clamp(t, 0.0, 1.0);
  switch (family) {
    case EaseFamily::Linear:
      return 1;
    case EaseFamily::Bezier:
      return bezier_slope(*this, t);
    default:
      break;
  }
  const bool in_out = mode == EaseMode::InOut;
  switch (mode) {
    case EaseMode::In:
      return in_slope(family, in_out, t);
    case EaseMode::Out:
      return in_slope(family, in_out, 1 - t);
    case EaseMode::InOut:
      // d/dt of in(2t)/2 is in'(2t); of 1 - in(2 - 2t)/2 it is in'(2 - 2t).
      return t < 0.5 ? in_slope(family, in_out, 2 * t) : in_slope(family, in_out, 2 - 2 * t);
  }
  return 1;
}

std::string Easing::name() const {
  if (family == EaseFamily::Linear) return "linear";
  if (family == EaseFamily::Bezier) {
    return "cubic-bezier(" + number_text(x1) + ", " + number_text(y1) + ", " + number_text(x2) +
           ", " + number_text(y2) + ")";
  }
  std::string n;
  for (const auto& [k, f] : families()) {
    if (f == family) n = k;
  }
  return n + (mode == EaseMode::In ? "-in" : mode == EaseMode::Out ? "-out" : "-in-out");
}

EaseParse parse_easing(std::string_view text) {
  if (text.rfind("cubic-bezier", 0) == 0) {
    std::string_view rest = text.substr(12);
    while (!rest.empty() && rest.front() == ' ') rest.remove_prefix(1);
    if (rest.empty() || rest.front() != '(' || rest.back() != ')') {
      return {std::nullopt, "write cubic-bezier as cubic-bezier(x1, y1, x2, y2)"};
    }
    return parse_bezier(rest.substr(1, rest.size() - 2));
  }
  Easing e;
  if (text == "linear") return {e, {}};
  // The quadratic shorthands, and the ease- spellings accepted since the first release.
  static const std::map<std::string, EaseMode, std::less<>> kShort = {
      {"in", EaseMode::In},      {"out", EaseMode::Out},      {"in-out", EaseMode::InOut},
      {"ease-in", EaseMode::In}, {"ease-out", EaseMode::Out}, {"ease-in-out", EaseMode::InOut}};
  if (auto it = kShort.find(text); it != kShort.end()) {
    e.family = EaseFamily::Quad;
    e.mode = it->second;
    return {e, {}};
  }
  for (const auto& [suffix, mode] : {std::pair{std::string_view("-in-out"), EaseMode::InOut},
                                     std::pair{std::string_view("-in"), EaseMode::In},
                                     std::pair{std::string_view("-out"), EaseMode::Out}}) {
    if (text.size() <= suffix.size() || text.substr(text.size() - suffix.size()) != suffix) {
      continue;
    }
    auto it = families().find(text.substr(0, text.size() - suffix.size()));
    if (it == families().end()) continue;
    e.family = it->second;
    e.mode = mode;
    return {e, {}};
  }
  return {std::nullopt, {}};
}

const std::vector<std::string>& easing_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n = {"linear", "in", "out", "in-out"};
    for (const auto& [k, f] : families()) {
      (void)f;
      for (const char* m : {"-in", "-out", "-in-out"}) n.push_back(k + m);
    }
    return n;
  }();
  return names;
}

std::string easing_name_list() {
  std::string families_text;
  for (const auto& [k, f] : families()) {
    (void)f;
    families_text += (families_text.empty() ? "" : ", ") + k;
  }
  return "easings: linear, in, out, in-out; " + families_text +
         ", each with -in, -out or -in-out; cubic-bezier(x1, y1, x2, y2)";
}

}  // namespace seqc::compiler
