// Motion steps into timeline segments: `move` (straight, eased or in explicit `steps`), `wait`
// (holds that re-send positions) and `through` (a C1 cubic Hermite curve through waypoints).
// Every mistake of a step is reported in the same run: a structural error does not hide the
// step's range, timing or easing errors.
#include <algorithm>
#include <cmath>

#include "compiler/frontend/source/units.hpp"
#include "compiler/frontend/step_parts.hpp"
#include "compiler/program/arm_kinematics.hpp"
#include "compiler/targets/servo_controller/servo_lowering_state.hpp"
#include "compiler/timeline/easing.hpp"
#include "runtime/protocol/group_download.hpp"

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

bool ServoLowering::resolve_targets(const std::vector<PositionEntry>& entries,
                                    const std::optional<Reporter::Note>& note,
                                    std::vector<std::optional<int>>& targets,
                                    std::vector<double>& degrees) {
  const std::vector<std::optional<int>> base = targets;  // where each servo is before
  std::fill(targets.begin(), targets.end(), std::nullopt);
  degrees.assign(targets.size(), std::nan(""));
  const double units_per_degree = robot_.degrees_to_units(1, true);
  const double zero = robot_.degrees_to_units(0, false);
  bool ok = true;
  for (const PositionEntry& e : entries) {
    const bool reflect = mirrored_ && robot_.mirror.count(e.output) != 0;
    const std::size_t servo = reflect ? robot_.mirror.at(e.output) : e.output;
    std::string how;
    double units = 0;
    if (e.value.relative) {
      double delta =
          e.value.degrees ? robot_.degrees_to_units(e.value.amount, true) : e.value.amount;
      if (reflect) delta = -delta;
      auto reached = relative_units(e, robot_.info.servos[servo].name, base[servo], delta, how,
                                    note, reporter_);
      if (!reached) {
        ok = false;
        continue;
      }
      units = *reached;
    } else {
      units = absolute_units(e, servo, reflect);
    }
    if (reflect) {
      how += std::string(how.empty() ? "" : ", ") + "mirrored from '" +
             robot_.info.servos[e.output].name + "'";
    }
    if (!check_limits(e, servo, units, how, note)) {
      ok = false;
      continue;
    }
    targets[servo] = static_cast<int>(std::llround(units));
    if (e.value.degrees && e.value.relative) {
      degrees[servo] = std::abs(e.value.amount);
    } else if (e.value.degrees && base[servo]) {
      degrees[servo] = std::abs(e.value.amount - (*base[servo] - zero) / units_per_degree);
    } else if (e.value.degrees) {
      degrees[servo] = std::abs(units - zero) / units_per_degree;
    }
  }
  return ok;
}

void ServoLowering::move_step(const YamlNode& step, const YamlNode& target, bool keys_ok) {
  std::vector<PositionEntry> inline_entries;
  std::optional<Reporter::Note> note;
  const std::vector<PositionEntry>* entries = nullptr;
  bool ok = true;
  TipTarget placed;
  const YamlNode* path = step.find("path");
  const bool line = path != nullptr && path->is_scalar() && path->scalar == "line";
  if (path != nullptr && !line) {
    reporter_.error(path->location,
                    "'path' is 'line' (the tip in a straight line); leave it out for the "
                    "joints' own curves");
    ok = false;
  }
  const bool has_tip = target.is_map() && target.find("tip") != nullptr;
  if (path != nullptr && !has_tip) {
    reporter_.error(path->location,
                    "'path' is the claw tip's and needs a 'tip' in the move, e.g. 'move: {tip: "
                    "[150mm, 0mm, 80mm]}'");
    ok = false;
  }
  if (has_tip) {
    // The other servos parse as usual; tip and pitch are the inverse kinematics' own.
    YamlNode rest = target;
    std::erase_if(rest.entries, [](const YamlEntry& e) {
      return e.first.scalar == "tip" || e.first.scalar == "pitch";
    });
    inline_entries = parse_positions(rest, "in this move");
    ok = tip_entries(step, target, inline_entries, placed) && ok;
    entries = &inline_entries;
  } else {
    entries =
        scopes_.move_entries(target, "servo", entries_parser(), inline_entries, note, reporter_);
    ok = entries != nullptr && ok;
    if (const YamlNode* e = step.find("elbow")) {
      reporter_.error(e->location,
                      "'elbow' chooses how the arm reaches a 'tip' and needs one in "
                      "the move, e.g. 'move: {tip: [150mm, 0mm, 80mm]}'");
      ok = false;
    }
  }

  const YamlNode* time_node = step.find("time");
  std::optional<ExactMs> total;
  if (time_node == nullptr && keys_ok) {
    reporter_.error(step.location, "this move needs a 'time', e.g. 'time: 500ms'");
  } else if (time_node != nullptr) {
    total = exact_time(*time_node, "'time'");
  }
  ok = ok && total.has_value();

  Easing ease;
  if (const YamlNode* e = step.find("ease")) {
    const std::optional<Easing> parsed = parse_ease(*e, reporter_);
    ok = ok && parsed.has_value();
    if (parsed) ease = *parsed;
  }
  std::optional<long long> steps;
  const YamlNode* steps_node = step.find("steps");
  if (steps_node != nullptr) {
    steps = parse_integer(*steps_node, 1, static_cast<long long>(capacity()), "'steps'", reporter_);
    ok = ok && steps.has_value();
  }
  std::optional<double> step_tolerance;
  double tolerance_mm = 1;  // a line's, of the tip
  if (const YamlNode* t = step.find("tolerance")) {
    const bool mm = t->is_scalar() && t->scalar.size() > 2 &&
                    t->scalar.compare(t->scalar.size() - 2, 2, "mm") == 0;
    if (line && mm) {
      double v = 0;
      if (!parse_decimal(std::string_view(t->scalar).substr(0, t->scalar.size() - 2), v) ||
          v <= 0) {
        reporter_.error(t->location,
                        "a line's 'tolerance' is a positive distance of the tip in "
                        "millimetres, e.g. 'tolerance: 1mm'");
        ok = false;
      }
      tolerance_mm = v;
    } else if (line) {
      reporter_.error(t->location,
                      "a line's 'tolerance' is the tip's distance from the line, "
                      "in millimetres, e.g. 'tolerance: 1mm'");
      ok = false;
    } else if (mm) {
      reporter_.error(t->location,
                      "a tolerance in millimetres is the tip's, for a 'path: line' "
                      "move; give the servos' in device units or degrees, e.g. "
                      "'tolerance: 1'");
      ok = false;
    } else {
      step_tolerance = parse_tolerance(*t);
      ok = ok && step_tolerance.has_value();
    }
  }
  if (line && steps_node != nullptr) {
    reporter_.error(steps_node->location,
                    "a 'path: line' move chooses its own actions to follow the line; leave out "
                    "'steps'");
    ok = false;
  }

  std::vector<std::optional<int>> targets = pos_;
  std::vector<double> degrees;
  if (entries != nullptr && !resolve_targets(*entries, note, targets, degrees)) ok = false;

  std::optional<std::uint64_t> rounded;
  if (total) {
    rounded = static_cast<std::uint64_t>(std::max<std::int64_t>(0, total->round()));
    if (*rounded < lsc::kMinActionMs) {
      reporter_.error(time_node->location, "time " + std::to_string(*rounded) +
                                               "ms is below the controller's minimum of 20ms per "
                                               "action");
      ok = false;
    } else if (*rounded > std::uint64_t{lsc::kMaxActionMs} * lsc::kMaxActions) {
      reporter_.error(time_node->location,
                      "'" + time_node->scalar +
                          "' is longer than a whole group can last (1,020 actions of 30s)");
      ok = false;
    }
  }
  if (!ok) return;

  // How many equal actions: `steps`, the file's `resolution` for an eased move (the uniform
  // expansion), or none given: a straight move is exact and an eased one is fitted.
  const std::uint64_t t = *rounded;
  std::uint64_t n = 0;
  if (line) {
    // The line's own actions (tip_line below).
  } else if (steps) {
    n = static_cast<std::uint64_t>(*steps);
  } else if (!ease.is_linear() && scopes_.resolution_ms()) {
    n = std::max<std::uint64_t>(1, t / *scopes_.resolution_ms());
  }
  if (n > 0 && t / n < lsc::kMinActionMs) {
    reporter_.error(steps_node != nullptr ? steps_node->location : time_node->location,
                    std::to_string(n) + " steps of " +
                        format_ms(static_cast<double>(t) / static_cast<double>(n)) +
                        " are shorter than the controller's 20ms minimum per action; use at most " +
                        std::to_string(t / lsc::kMinActionMs) + " steps");
    return;
  }
  const bool shaped = n > 1 || (n == 0 && !ease.is_linear());
  for (std::size_t servo = 0; servo < targets.size() && shaped; ++servo) {
    if (!targets[servo] || pos_[servo]) continue;
    reporter_.error(step.location,
                    "'" + robot_.info.servos[servo].name +
                        "' has no known position before this move, so it cannot be " +
                        (n > 1 ? "split into " + std::to_string(n) + " actions" : "eased") +
                        "; move it to an absolute position first");
    return;
  }

  const double tol = step_tolerance.value_or(tolerance());
  const ExactMs start = now_;
  const ExactMs end = now_ + *total;
  check_first_move(targets, *total, step.location);
  std::vector<KinematicFinding> findings;
  if (line) {
    if (tip_line(step, placed, targets, start, end, ease, tolerance_mm, tol, findings)) {
      report_kinematics(findings);
      now_ = end;
    }
    return;
  }
  if (has_tip) {
    // Where the tip was (its end when the joints were unknown) and where it goes, for plots.
    TimelineTipMove m{start.value(), end.value(), placed.point, placed.point, false};
    if (std::all_of(placed.joints.begin(), placed.joints.end(),
                    [&](std::size_t j) { return pos_[j].has_value(); })) {
      m.from = backend::arm_points(*robot_.info.arm, [&](std::string_view name) {
                 return static_cast<double>(*pos_[robot_.names.find(name)->second]);
               }).tip;
    }
    timeline_.tip_moves.push_back(m);
  }
  for (std::size_t servo = 0; servo < targets.size(); ++servo) {
    if (!targets[servo]) continue;
    if (!claim(servo, step.location)) return;
    const double from = pos_[servo] ? *pos_[servo] : *targets[servo];
    const double to = *targets[servo];
    Segment seg;
    seg.start = start;
    seg.end = end;
    seg.from = from;
    seg.to = to;
    seg.tolerance = tol;
    seg.at = step.location;
    if (n > 1) {  // `steps`: equal pieces, the servo reaching f(k/n) of the way after piece k
      double prev = from;
      Segment fastest;  // the controller moves in these straight pieces: check the fastest
      for (std::uint64_t k = 1; k <= n; ++k) {
        Segment piece = seg;
        piece.kind = CurveKind::Linear;
        piece.keep_boundaries = true;
        piece.start = start + *total * ExactMs::ratio(k - 1, n);
        piece.end = start + *total * ExactMs::ratio(k, n);
        piece.from = prev;
        piece.to = k == n ? to
                          : static_cast<double>(
                                std::llround(from + (to - from) * ease.at(static_cast<double>(k) /
                                                                          static_cast<double>(n))));
        prev = piece.to;
        if (k == 1 || std::abs(piece.to - piece.from) > std::abs(fastest.to - fastest.from)) {
          fastest = piece;
        }
        add_segment(servo, piece);
      }
      check_kinematics(servo, fastest, degrees[servo], note, findings);
    } else {
      seg.kind = ease.is_linear() || n == 1 ? CurveKind::Linear : CurveKind::Eased;
      seg.easing = ease;
      if (seg.kind == CurveKind::Eased && !check_overshoot(servo, seg, step.location, note)) {
        return;
      }
      check_kinematics(servo, seg, degrees[servo], note, findings);
      add_segment(servo, seg);
    }
    pos_[servo] = *targets[servo];
  }
  report_kinematics(findings);
  count_actions(n > 0 ? n : (t + lsc::kMaxActionMs - 1) / lsc::kMaxActionMs, step.location);
  now_ = end;
}

void ServoLowering::wait_step(const YamlNode& step, const YamlNode& value) {
  auto total = exact_time(value, "'wait'");
  if (!total) return;
  const std::int64_t t = total->round();
  if (t < static_cast<std::int64_t>(lsc::kMinActionMs)) {
    reporter_.error(value.location, "wait of " + std::to_string(t) +
                                        "ms is below the controller's minimum of 20ms per "
                                        "action");
    return;
  }
  // Inside a track a wait holds that track's servos; elsewhere every servo with a position.
  std::vector<std::size_t> held;
  if (const TrackClaims::Track* track = claims_.track()) {
    held = track->outputs;
  } else {
    for (std::size_t i = 0; i < pos_.size(); ++i) {
      if (pos_[i]) held.push_back(i);
    }
  }
  if (held.empty() && claims_.in_block()) {
    // A track that has moved nothing yet waits: its servos simply do not move yet.
    count_actions((static_cast<std::uint64_t>(t) + lsc::kMaxActionMs - 1) / lsc::kMaxActionMs,
                  step.location);
    now_ += *total;
    return;
  }
  if (held.empty()) {
    reporter_.error(step.location,
                    "nothing to hold: no servo has a position yet (a controller action carries "
                    "positions); move first, then wait (to start some servos later than others, "
                    "give their first step an 'at:' in a 'together' track)");
    return;
  }
  for (std::size_t servo : held) {
    Segment seg;
    seg.kind = CurveKind::Hold;
    seg.start = now_;
    seg.end = now_ + *total;
    seg.from = seg.to = *pos_[servo];
    seg.tolerance = tolerance();
    seg.at = step.location;
    add_segment(servo, seg);
  }
  count_actions((static_cast<std::uint64_t>(t) + lsc::kMaxActionMs - 1) / lsc::kMaxActionMs,
                step.location);
  now_ += *total;
}

void ServoLowering::add_segment(std::size_t servo, Segment segment) {
  timeline_.add(servo, segment);
}

bool ServoLowering::claim(std::size_t servo, Location at) {
  return claims_.claim(servo, "'" + robot_.info.servos[servo].name + "'", "moves",
                       "a servo may move in one track of a 'together' only", at, reporter_);
}

void ServoLowering::count_actions(std::uint64_t n, Location at) {
  min_actions_ = min_actions_ + n < min_actions_ ? UINT64_MAX : min_actions_ + n;
  if (min_actions_ > capacity() && !over_budget_at_) over_budget_at_ = at;
}

bool ServoLowering::check_overshoot(std::size_t servo, const Segment& segment, Location at,
                                    const std::optional<Reporter::Note>& note) {
  const ServoInfo& info = robot_.info.servos[servo];
  double lo = std::min(segment.from, segment.to), hi = std::max(segment.from, segment.to);
  const double t0 = segment.start.value(), t1 = segment.end.value();
  for (int i = 1; i < kCurveSamples; ++i) {
    const double v = segment.value(t0 + (t1 - t0) * i / kCurveSamples);
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  const long long low = std::llround(lo), high = std::llround(hi);
  if (low >= info.min && high <= info.max) return true;
  const std::string curve =
      segment.kind == CurveKind::Eased ? "this " + segment.easing.name() + " curve" : "this curve";
  reporter_.error(at,
                  "'" + info.name + "' would overshoot to " +
                      std::to_string(high > info.max ? high : low) + " on " + curve +
                      (high > info.max ? ", above its max " + std::to_string(info.max)
                                       : ", below its min " + std::to_string(info.min)),
                  note);
  return false;
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
  const bool too_fast = info.max_speed && speed > *info.max_speed + 1e-9;
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
    // A vertical tangent (circ, some cubic-beziers) has no finite peak to print.
    f.value = std::isinf(speed) ? "unbounded speed" : number(speed * per_unit, 0) + u + "/s";
    f.limit = number(*info.max_speed * per_unit, 0) + u + "/s";
    findings.push_back(f);
  }
  if (too_sudden) {
    f.speed = false;
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
          g.value != f.value || g.limit != f.limit || g.shape != f.shape ||
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
    if (names.size() == 1) {
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
    if (!targets[servo] || pos_[servo] || !info.max_speed || *info.max_speed <= 0) continue;
    const int target = *targets[servo];
    const int from = target - info.min >= info.max - target ? info.min : info.max;
    const double needs = std::abs(target - from) * 1000.0 / *info.max_speed;
    if (takes + 1e-9 < needs) slow.push_back({servo, from, needs});
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
