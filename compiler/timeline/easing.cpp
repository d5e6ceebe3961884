// The textbook easing formulas (the ones animation libraries and CSS share); each family's
// -in curve f gives -out as 1 - f(1 - t) and -in-out as f(2t)/2, then 1 - f(2 - 2t)/2, except
// where the usual definition differs (back and elastic in-out use their own constants).
#include "compiler/timeline/easing.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>

namespace seqc::compiler {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kBack = 1.70158;             // overshoot of about 10 %
constexpr double kBackInOut = kBack * 1.525;  // the in-out variant's larger constant

double bounce_out(double t) {
  constexpr double n = 7.5625;
  constexpr double d = 2.75;
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

// The -in curve of a family whose -out and -in-out follow from it.
double in_curve(EaseFamily f, double t) {
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
      return t <= 0 ? 0 : std::pow(2, 10 * t - 10);
    case EaseFamily::Circ:
      return 1 - std::sqrt(std::max(0.0, 1 - t * t));
    case EaseFamily::Back:
      return (kBack + 1) * t * t * t - kBack * t * t;
    case EaseFamily::Bounce:
      return 1 - bounce_out(1 - t);
    default:
      return t;
  }
}

double elastic(EaseMode mode, double t) {
  if (t <= 0) return 0;
  if (t >= 1) return 1;
  constexpr double c4 = 2 * kPi / 3;
  constexpr double c5 = 2 * kPi / 4.5;
  switch (mode) {
    case EaseMode::In:
      return -std::pow(2, 10 * t - 10) * std::sin((10 * t - 10.75) * c4);
    case EaseMode::Out:
      return std::pow(2, -10 * t) * std::sin((10 * t - 0.75) * c4) + 1;
    case EaseMode::InOut:
      return t < 0.5 ? -(std::pow(2, 20 * t - 10) * std::sin((20 * t - 11.125) * c5)) / 2
                     : std::pow(2, -20 * t + 10) * std::sin((20 * t - 11.125) * c5) / 2 + 1;
  }
  return t;
}

double back_in_out(double t) {
  constexpr double c = kBackInOut;
  if (t < 0.5) return std::pow(2 * t, 2) * ((c + 1) * 2 * t - c) / 2;
  return (std::pow(2 * t - 2, 2) * ((c + 1) * (t * 2 - 2) + c) + 2) / 2;
}

// CSS cubic-bezier: the curve from (0,0) to (1,1) with control points (x1,y1), (x2,y2); the
// value at time t is y(s) where x(s) = t. x(s) is monotonic because x1, x2 are in [0, 1].
double bezier(const Easing& e, double t) {
  auto coord = [](double p1, double p2, double s) {
    const double u = 1 - s;
    return 3 * u * u * s * p1 + 3 * u * s * s * p2 + s * s * s;
  };
  auto slope = [](double p1, double p2, double s) {
    const double u = 1 - s;
    return 3 * u * u * p1 + 6 * u * s * (p2 - p1) + 3 * s * s * (1 - p2);
  };
  double s = t;
  for (int i = 0; i < 8; ++i) {  // Newton, then bisection if it stalls
    const double dx = coord(e.x1, e.x2, s) - t;
    if (std::abs(dx) < 1e-12) return coord(e.y1, e.y2, s);
    const double d = slope(e.x1, e.x2, s);
    if (std::abs(d) < 1e-9) break;
    s -= dx / d;
    if (s < 0 || s > 1) break;
  }
  double lo = 0, hi = 1;
  s = t;
  for (int i = 0; i < 60; ++i) {
    const double x = coord(e.x1, e.x2, s);
    if (std::abs(x - t) < 1e-12) break;
    (x < t ? lo : hi) = s;
    s = (lo + hi) / 2;
  }
  return coord(e.y1, e.y2, s);
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
    case EaseFamily::Elastic:
      return elastic(mode, t);
    case EaseFamily::Back:
      if (mode == EaseMode::InOut) return back_in_out(t);
      break;
    default:
      break;
  }
  switch (mode) {
    case EaseMode::In:
      return in_curve(family, t);
    case EaseMode::Out:
      return 1 - in_curve(family, 1 - t);
    case EaseMode::InOut:
      return t < 0.5 ? in_curve(family, 2 * t) / 2 : 1 - in_curve(family, 2 - 2 * t) / 2;
  }
  return t;
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

}  // namespace seqc::compiler
