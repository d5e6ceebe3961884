// Motion steps into timeline segments: `move` (straight, eased or in explicit `steps`), `wait`
// (holds that re-send positions) and `through` (a C1 cubic Hermite curve through waypoints).
// Every mistake of a step is reported in the same run: a structural error does not hide the
// step's range, timing or easing errors.
#include <algorithm>
#include <cmath>

#include "compiler/lang/servo_lowering_state.hpp"
#include "compiler/lang/step_parts.hpp"
#include "compiler/source/units.hpp"
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
  const std::vector<PositionEntry>* entries =
      scopes_.move_entries(target, "servo", entries_parser(), inline_entries, note, reporter_);
  bool ok = entries != nullptr;

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
  if (const YamlNode* t = step.find("tolerance")) {
    step_tolerance = parse_tolerance(*t);
    ok = ok && step_tolerance.has_value();
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
  if (steps) {
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
      check_kinematics(servo, fastest, degrees[servo], note);
    } else {
      seg.kind = ease.is_linear() || n == 1 ? CurveKind::Linear : CurveKind::Eased;
      seg.easing = ease;
      if (seg.kind == CurveKind::Eased && !check_overshoot(servo, seg, step.location, note)) {
        return;
      }
      check_kinematics(servo, seg, degrees[servo], note);
      add_segment(servo, seg);
    }
    pos_[servo] = *targets[servo];
  }
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
  if (track_ != nullptr) {
    held = track_->servos;
  } else {
    for (std::size_t i = 0; i < pos_.size(); ++i) {
      if (pos_[i]) held.push_back(i);
    }
  }
  if (held.empty() && track_ != nullptr) {
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
  // One track of each running block: the innermost block is checked first (its tracks are
  // the closest places to name).
  for (auto block = blocks_.rbegin(); block != blocks_.rend(); ++block) {
    auto it = block->claimed.find(servo);
    if (it == block->claimed.end() || it->second.first == block->track->name) continue;
    const std::string& name = robot_.info.servos[servo].name;
    reporter_.error(
        at,
        "'" + name + "' moves in two tracks, '" + it->second.first + "' and '" +
            block->track->name + "'; a servo may move in one track of a 'together' only",
        Reporter::Note{it->second.second,
                       "'" + name + "' moves in track '" + it->second.first + "' here"});
    return false;
  }
  for (Block& block : blocks_) {
    block.claimed.try_emplace(servo, block.track->name, at);
    std::vector<std::size_t>& servos = block.track->servos;
    if (std::find(servos.begin(), servos.end(), servo) == servos.end()) servos.push_back(servo);
  }
  return true;
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

void ServoLowering::check_kinematics(std::size_t servo, const Segment& segment, double degrees,
                                     const std::optional<Reporter::Note>& note) {
  const ServoInfo& info = robot_.info.servos[servo];
  if (!info.max_speed && !info.max_accel) return;
  const double t0 = segment.start.value(), t1 = segment.end.value();
  const double ms = t1 - t0;
  if (ms <= 0) return;
  // Peak speed (units/s) and acceleration (units/s^2) along the curve, by finite differences.
  double speed = std::abs(segment.to - segment.from) * 1000.0 / ms;
  double accel = 0;
  if (segment.kind != CurveKind::Linear && segment.kind != CurveKind::Hold) {
    // Central differences at kCurveSamples + 1 instants (both ends and the middle included).
    const double h = ms / kCurveSamples;
    const double d = ms * 1e-6;
    auto velocity = [&](double t) {
      const double a = std::max(t0, t - d), b = std::min(t1, t + d);
      return (segment.value(b) - segment.value(a)) * 1000.0 / (b - a);
    };
    double prev_v = velocity(t0);
    for (int i = 0; i <= kCurveSamples; ++i) {
      const double v = velocity(t0 + h * i);
      speed = std::max(speed, std::abs(v));
      if (i > 0) accel = std::max(accel, std::abs(v - prev_v) * 1000.0 / h);
      prev_v = v;
    }
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
  const std::string moved = number(in_degrees ? degrees : distance, 1) + u + " in " + format_ms(ms);
  const bool curved = segment.kind != CurveKind::Linear;
  const std::string shape =
      segment.kind == CurveKind::Eased ? " on this " + segment.easing.name() + " curve" : "";
  if (too_fast) {
    const std::string message =
        moved + (curved ? " peaks at " : " is ") + number(speed * per_unit, 0) + u + "/s" + shape +
        ", above " + info.name + "'s " + number(*info.max_speed * per_unit, 0) + u + "/s";
    reporter_.warning(segment.at, message, note);
    timeline_.warnings.push_back({segment.start.value(), servo, message});
  }
  if (too_sudden) {
    const std::string message = moved + " accelerates at up to " + number(accel * per_unit, 0) + u +
                                "/s^2" + shape + ", above " + info.name + "'s " +
                                number(*info.max_accel * per_unit, 0) + u + "/s^2";
    reporter_.warning(segment.at, message, note);
    timeline_.warnings.push_back({segment.start.value(), servo, message});
  }
}

}  // namespace seqc::compiler
