// The checks of a motion step's segments: a curve overshooting the servo's limits, speed and
// acceleration against max_speed and max_accel from the curve's exact derivative (servos that
// break a limit alike get one warning), and a first move that may start anywhere. A curve
// vertical somewhere is judged by the least speed that keeps within its tolerance.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "base/units.hpp"
#include "compiler/frontend/step_parts.hpp"
#include "compiler/targets/servo_controller/servo_lowering_state.hpp"
#include "compiler/timeline/easing.hpp"
#include "compiler/timeline/speed_within_tolerance.hpp"
#include "protocol/lsc/group_download.hpp"

namespace seqc::compiler {
namespace {

constexpr int kCurveSamples = 256;  // for peaks of speed, acceleration and overshoot

std::string number(double v, int decimals) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  std::string s = buf;
  if (s.find('.') != std::string::npos) {
    while (s.back() == '0') s.pop_back();
    if (s.back() == '.') s.pop_back();
  }
  return s;
}

}  // namespace

bool ServoLowering::check_overshoot(std::size_t servo, const Segment& segment, Location at,
                                    const std::optional<Reporter::Note>& note) {
  const ServoInfo& info = robot_.info.servos[servo];
  return check_curve_limits(segment, info.name, info.min, info.max, at, note, reporter_);
}

namespace {

// Where |f| peaks on [a, b], given that it is largest at sample `best` of `samples` evenly
// spaced ones: golden-section search on the two intervals beside that sample (enough for the
// smooth curves and the piecewise bounces, whose peaks lie between samples).
template <typename F>
double refine_peak(F f, double a, double b, int samples, int best, double peak) {
  const double h = (b - a) / samples;
  constexpr double g = 0.6180339887498949;
  for (const int side : {-1, 1}) {
    double lo = a + h * best, hi = lo + h * side;
    if (hi < a || hi > b) continue;
    if (lo > hi) std::swap(lo, hi);
    for (int i = 0; i < 60; ++i) {
      const double m1 = hi - g * (hi - lo), m2 = lo + g * (hi - lo);
      const double f1 = std::abs(f(m1)), f2 = std::abs(f(m2));
      // Every probe counts: at a bounce the peak is a jump, and the final midpoint may land on
      // its low side.
      peak = std::max({peak, f1, f2});
      if (f1 < f2) {
        lo = m1;
      } else {
        hi = m2;
      }
    }
  }
  return peak;
}

std::string servo_names(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "'" : ", '") + n + "'";
  return out;
}

}  // namespace

void ServoLowering::check_kinematics(std::size_t servo, const Segment& segment, double degrees,
                                     const std::optional<Reporter::Note>& note,
                                     std::vector<KinematicFinding>& findings) {
  const ServoInfo& info = robot_.info.servos[servo];
  if (!info.max_speed && !info.max_accel) return;
  const double t0 = segment.start.value(), t1 = segment.end.value();
  const double ms = t1 - t0;
  if (ms <= 0) return;
  // Peak speed (units/s) from the curve's exact derivative, and peak acceleration (units/s^2)
  // from differences of that derivative between instants inside the segment: nothing is ever
  // sampled across an end, where a curve meets the next one.
  double speed = std::abs(segment.to - segment.from) * 1000.0 / ms;
  double accel = 0;
  if (segment.kind != CurveKind::Linear && segment.kind != CurveKind::Hold) {
    const double h = ms / kCurveSamples;
    auto velocity = [&](double t) { return segment.velocity(t) * 1000.0; };
    double prev_v = velocity(t0);
    int best = 0;
    double peak = std::abs(prev_v);
    for (int i = 1; i <= kCurveSamples; ++i) {
      const double v = velocity(t0 + h * i);
      if (std::abs(v) > peak) {
        peak = std::abs(v);
        best = i;
      }
      accel = std::max(accel, std::abs(v - prev_v) * 1000.0 / h);
      prev_v = v;
    }
    speed = std::isinf(peak) ? peak : refine_peak(velocity, t0, t1, kCurveSamples, best, peak);
  }
  // A vertical curve has no finite peak: the controller keeps within the tolerance of it, so
  // what it must reach is the gentlest motion within the tolerance (speed_within_tolerance.hpp).
  std::optional<double> within;
  if (std::isinf(speed) && info.max_speed) {
    // The bound is (distance / time) x a factor of the easing and tolerance / distance alone,
    // so moves of one shape share it whatever their time.
    const double distance = std::abs(segment.to - segment.from);
    const auto key = std::make_pair(segment.easing.name(), segment.tolerance / distance);
    auto known = speeds_within_tolerance_.find(key);
    if (known == speeds_within_tolerance_.end()) {
      const double factor =
          speed_within_tolerance(segment, segment.tolerance) * ms / 1000.0 / distance;
      known = speeds_within_tolerance_.emplace(key, factor).first;
    }
    within = known->second * distance * 1000.0 / ms;
  }
  const bool too_fast = info.max_speed && (within ? *within : speed) > *info.max_speed + 1e-9;
  const bool too_sudden = info.max_accel && accel > *info.max_accel + 1e-9;
  if (!too_fast && !too_sudden) return;
  // In the author's units: degrees as written, else device units.
  const double distance = std::abs(segment.to - segment.from);
  const bool in_degrees = !std::isnan(degrees);
  const double per_unit = !in_degrees    ? 1.0
                          : distance > 0 ? degrees / distance
                                         : 1.0 / robot_.degrees_to_units(1, true);
  const std::string u = in_degrees ? "deg" : "";
  KinematicFinding f;
  f.servo = servo;
  f.at = segment.at;
  f.start_ms = segment.start.value();
  f.note = note;
  f.moved = number(in_degrees ? degrees : distance, 1) + u + " in " + format_ms(ms);
  f.shape = segment.kind == CurveKind::Eased ? " on this " + segment.easing.name() + " curve" : "";
  f.curved = segment.kind != CurveKind::Linear;
  if (too_fast) {
    f.speed = true;
    // A vertical tangent (circ, some cubic-beziers) has no finite peak to print: its bound
    // within the tolerance, to the hundredth (4999.5/s, 498.75/s).
    f.value =
        within ? number(*within * per_unit, 2) + u + "/s" : number(speed * per_unit, 0) + u + "/s";
    if (within) f.within = " within a tolerance of " + number(segment.tolerance, 3);
    f.limit = number(*info.max_speed * per_unit, 0) + u + "/s";
    findings.push_back(f);
  }
  if (too_sudden) {
    f.speed = false;
    f.within.clear();
    f.value =
        std::isinf(accel) ? "unbounded acceleration" : number(accel * per_unit, 0) + u + "/s^2";
    f.limit = number(*info.max_accel * per_unit, 0) + u + "/s^2";
    findings.push_back(f);
  }
}

void ServoLowering::report_kinematics(const std::vector<KinematicFinding>& findings) {
  // One diagnostic per fact: the servos of one step that break the same limit in the same way
  // (a mirrored pair, a pose moving three joints alike) are named together.
  std::vector<bool> done(findings.size(), false);
  for (std::size_t i = 0; i < findings.size(); ++i) {
    if (done[i]) continue;
    const KinematicFinding& f = findings[i];
    std::vector<std::string> names;
    std::vector<std::size_t> servos;
    for (std::size_t j = i; j < findings.size(); ++j) {
      const KinematicFinding& g = findings[j];
      if (done[j] || g.speed != f.speed || g.at != f.at || g.moved != f.moved ||
          g.value != f.value || g.limit != f.limit || g.shape != f.shape || g.within != f.within ||
          g.note.has_value() != f.note.has_value() ||
          (g.note && (g.note->at != f.note->at || g.note->message != f.note->message))) {
        continue;
      }
      done[j] = true;
      names.push_back(robot_.info.servos[g.servo].name);
      servos.push_back(g.servo);
    }
    const bool unbounded = f.value.rfind("unbounded", 0) == 0;
    std::string message;
    if (!f.within.empty()) {
      message = names.size() == 1
                    ? f.moved + " needs at least " + f.value + f.shape + f.within + ", above " +
                          names[0] + "'s " + f.limit
                    : "servos " + servo_names(names) + " move " + f.moved + " and need at least " +
                          f.value + f.shape + f.within + ", above their " + f.limit;
    } else if (names.size() == 1) {
      message = f.speed ? f.moved +
                              (unbounded  ? " has "
                               : f.curved ? " peaks at "
                                          : " is ") +
                              f.value + f.shape + ", above " + names[0] + "'s " + f.limit
                        : f.moved + (unbounded ? " has " : " accelerates at up to ") + f.value +
                              f.shape + ", above " + names[0] + "'s " + f.limit;
    } else {
      const std::string who = "servos " + servo_names(names) + " move " + f.moved;
      message = f.speed ? who +
                              (unbounded  ? " with "
                               : f.curved ? " and peak at "
                                          : " at ") +
                              f.value + f.shape + ", above their " + f.limit
                        : who + (unbounded ? " with " : " and accelerate at up to ") + f.value +
                              f.shape + ", above their " + f.limit;
    }
    reporter_.warning(f.at, message, f.note);
    for (std::size_t servo : servos) timeline_.warnings.push_back({f.start_ms, servo, message});
  }
}

std::optional<FarEnd> far_end(const ServoInfo& info, int target) {
  if (!info.max_speed || *info.max_speed <= 0) return std::nullopt;
  const int from = target - info.min >= info.max - target ? info.min : info.max;
  return FarEnd{from, std::abs(target - from) * 1000.0 / *info.max_speed};
}

void ServoLowering::check_first_move(const std::vector<std::optional<int>>& targets, ExactMs time,
                                     Location at) {
  // The robot may be anywhere when a group starts: a servo's first move may have to come from
  // the far end of its limits.
  struct Slow {
    std::size_t servo;
    int from;
    double needs_ms;
  };
  std::vector<Slow> slow;
  const double takes = time.value();
  for (std::size_t servo = 0; servo < targets.size(); ++servo) {
    const ServoInfo& info = robot_.info.servos[servo];
    if (!targets[servo] || pos_[servo]) continue;
    const std::optional<FarEnd> far = far_end(info, *targets[servo]);
    if (far && takes + 1e-9 < far->needs_ms) slow.push_back({servo, far->from, far->needs_ms});
  }
  if (slow.empty()) return;
  const auto worst = std::max_element(slow.begin(), slow.end(), [](const Slow& a, const Slow& b) {
    return a.needs_ms < b.needs_ms;
  });
  const ServoInfo& info = robot_.info.servos[worst->servo];
  // Rounded up to a hundredth of a second, so the time it names is safe as written.
  const std::string needs = number(std::ceil(worst->needs_ms / 10 - 1e-9) / 100, 2) + " s";
  const std::string range = std::to_string(info.min) + ".." + std::to_string(info.max);
  const std::string tail = "from " + std::to_string(worst->from) + " it needs " + needs +
                           " at max_speed " + number(*info.max_speed, 0) + "/s; this move takes " +
                           number(takes / 1000, 3) + " s";
  std::string message;
  if (slow.size() == 1) {
    message = "first move of '" + info.name + "' may start anywhere in " + range + "; " + tail;
  } else {
    std::vector<std::string> names;
    for (const Slow& s : slow) names.push_back(robot_.info.servos[s.servo].name);
    message = "first move of servos " + servo_names(names) +
              " may start anywhere in their limits; the slowest, '" + info.name + "' (" + range +
              "): " + tail;
  }
  reporter_.warning(at, message);
  for (const Slow& s : slow) timeline_.warnings.push_back({now_.value(), s.servo, message});
}

}  // namespace seqc::compiler
