// Motion steps into timeline segments: `move` (straight, eased or in explicit `steps`), `wait`
// (holds that re-send positions) and `through` (a C1 cubic Hermite curve through waypoints).
// Every mistake of a step is reported in the same run: a structural error does not hide the
// step's range, timing or easing errors.
#include <algorithm>
#include <cmath>

#include "base/units.hpp"
#include "compiler/frontend/step_parts.hpp"
#include "compiler/program/arm_kinematics.hpp"
#include "compiler/targets/servo_controller/servo_lowering_state.hpp"
#include "compiler/timeline/easing.hpp"
#include "protocol/lsc/group_download.hpp"

namespace seqc::compiler {

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
      std::optional<int> from = base[servo];
      if (!from) {
        from = standing(servo, e, note);
        if (!from) {
          ok = false;
          continue;
        }
        pos_[servo] = *from;  // the move starts where the servo stands
      }
      auto reached =
          relative_units(e, robot_.info.servos[servo].name, from, delta, how, note, reporter_);
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

std::optional<int> ServoLowering::standing(std::size_t servo, const PositionEntry& e,
                                           const std::optional<Reporter::Note>& note) {
  const ServoInfo& info = robot_.info.servos[servo];
  if (!servos_report_positions(robot_.info)) {
    std::string how;
    relative_units(e, info.name, std::nullopt, 0, how, note, reporter_);  // says it is unknown
    return std::nullopt;
  }
  if (std::find(start_reads_.begin(), start_reads_.end(), info.id) == start_reads_.end()) {
    start_reads_.push_back(info.id);
  }
  if (const auto read = start_.read.find(info.id); read != start_.read.end()) return read->second;
  if (start_.assume_home) {
    reporter_.note(e.at, "'" + info.name + "' moves " + e.written +
                             " from where the robot stands; checked here from its home " +
                             std::to_string(info.home) +
                             " ('seqc upload --run' and 'seqc play' read where it stands)");
    return info.home;
  }
  reporter_.error(e.at,
                  "'" + info.name + "' moves " + e.written +
                      " from where the robot stands, which only a reading of its servos "
                      "tells: 'seqc upload --run' and 'seqc play' read them first; or move '" +
                      info.name + "' to an absolute position before this",
                  note);
  return std::nullopt;
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
    // `elbow: up` or `down` inside the move chooses the solution, as it does beside `time`: in
    // a tip move the elbow's servo is placed by the tip, so those words name no position.
    std::erase_if(rest.entries, [](const YamlEntry& e) {
      return e.first.scalar == "tip" || e.first.scalar == "pitch" ||
             (e.first.scalar == "elbow" && e.second.is_scalar() &&
              (e.second.scalar == "up" || e.second.scalar == "down"));
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
  // A move longer than one action is split too: its first part would take the servo all the
  // way, from wherever it is, in a fraction of the time.
  const bool too_long = !line && n == 0 && t > lsc::kMaxActionMs;
  const bool shaped = n > 1 || (n == 0 && !ease.is_linear()) || too_long;
  for (std::size_t servo = 0; servo < targets.size() && shaped; ++servo) {
    if (!targets[servo] || pos_[servo]) continue;
    const std::string split = n > 1 ? "split into " + std::to_string(n) + " actions"
                              : too_long
                                  ? "split into actions (" + format_ms(static_cast<double>(t)) +
                                        " is longer than the controller's 30s per action)"
                                  : "eased";
    reporter_.error(step.location, "'" + robot_.info.servos[servo].name +
                                       "' has no known position before this move, so it cannot "
                                       "be " +
                                       split + "; move it to an absolute position first");
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
      m.from = compiler::arm_points(*robot_.info.arm, [&](std::string_view name) {
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
    seg.from_unknown = !pos_[servo];
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
  record_arm_move([&](std::size_t servo) { return targets[servo].has_value(); }, start, end,
                  step.location, has_tip, 0);
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
  if (held.empty()) {
    // An opening rest (or a track that has moved nothing yet): the servos stay where they
    // stand, and the actions until the first move name none of them.
    count_actions((static_cast<std::uint64_t>(t) + lsc::kMaxActionMs - 1) / lsc::kMaxActionMs,
                  step.location);
    now_ += *total;
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
  if (min_actions_ > budget() && !over_budget_at_) {
    over_budget_at_ = at;
    over_budget_time_ = now_;
    over_budget_notes_ = reporter_.chain();
  }
}

}  // namespace seqc::compiler
