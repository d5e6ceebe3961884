// A `path: line` move of the claw's tip: its joints' straight pieces from the line search
// (targets/servo_controller/tip_line.hpp) added to the timeline, and the line searched again
// once every track is known, so that other tracks' boundaries inside it are its own action ends.
#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "base/units.hpp"
#include "compiler/targets/servo_controller/servo_lowering_state.hpp"
#include "compiler/targets/servo_controller/tip_line.hpp"
#include "compiler/targets/servo_controller/tip_text.hpp"
#include "protocol/lsc/group_download.hpp"

namespace seqc::compiler {
namespace {

// Where along a line a fraction of it falls: "40% of the line"; past its ends (an overshooting
// ease) "10% of the line's length before its start" or "... past its end". `inside` tells which.
std::string along_line(double fraction, bool& inside) {
  // Adding 0.0 turns a -0 (a fraction just below 0 rounded) into 0.
  const double percent = std::round(fraction * 100) + 0.0;
  inside = percent >= 0 && percent <= 100;
  if (percent < 0) return fmt::format("{:g}% of the line's length before its start", -percent);
  if (percent > 100) return fmt::format("{:g}% of the line's length past its end", percent - 100);
  return fmt::format("{:g}% of the line", percent);
}

}  // namespace

bool ServoLowering::tip_line(const YamlNode& step, const TipTarget& placed,
                             const std::vector<std::optional<int>>& targets, ExactMs start,
                             ExactMs end, const Easing& ease, double tolerance_mm,
                             double tolerance_units, std::vector<KinematicFinding>& findings) {
  const ArmGeometry& arm = *robot_.info.arm;
  const ArmJoint* joints[] = {&arm.base, &arm.shoulder, &arm.elbow, &arm.wrist};
  compiler::TipLineRequest request;
  request.arm = arm;
  double pitch_from = 0;
  for (std::size_t j = 0; j < 4; ++j) {
    const std::size_t servo = placed.joints[j];
    request.from[j] = *pos_[servo];
    request.min[j] = robot_.info.servos[servo].min;
    request.max[j] = robot_.info.servos[servo].max;
    if (j > 0)
      pitch_from += joints[j]->sign * (*pos_[servo] - joints[j]->zero) * arm.degrees_per_unit;
  }
  request.to = placed.point;
  request.pitch_from = pitch_from;
  request.pitch_to = placed.pitch;
  request.elbow_up = placed.elbow_up;
  request.ease = ease;
  request.start_ms = static_cast<std::uint32_t>(std::max<std::int64_t>(0, start.round()));
  request.end_ms = static_cast<std::uint32_t>(std::max<std::int64_t>(0, end.round()));
  request.tolerance_mm = tolerance_mm;
  request.min_action_ms = lsc::kMinActionMs;
  request.max_action_ms = lsc::kMaxActionMs;
  request.model = robot_.controller;
  // The move's other servos, on the line's actions.
  std::vector<std::size_t> others;
  for (std::size_t servo = 0; servo < targets.size(); ++servo) {
    if (!targets[servo] ||
        std::find(placed.joints.begin(), placed.joints.end(), servo) != placed.joints.end()) {
      continue;
    }
    Segment seg;
    seg.kind = ease.is_linear() ? CurveKind::Linear : CurveKind::Eased;
    seg.easing = ease;
    seg.start = start;
    seg.end = end;
    seg.from = pos_[servo] ? *pos_[servo] : *targets[servo];
    seg.to = *targets[servo];
    if (seg.kind == CurveKind::Eased && !check_overshoot(servo, seg, step.location, std::nullopt)) {
      return false;
    }
    others.push_back(servo);
    request.others.push_back({seg.from, seg.to, tolerance_units, {}});
  }
  const compiler::TipLineResult fit = compiler::fit_tip_line(request);

  if (const auto& p = fit.problem) {
    using Kind = compiler::TipLineProblem::Kind;
    const Location at = step.find("path")->location;
    bool inside = true;
    const std::string along = along_line(p->fraction, inside);
    const std::string where = fmt::format("{} {}, {}", inside ? "at" : "where the ease runs", along,
                                          point_text(p->point));
    switch (p->kind) {
      case Kind::BelowTable:
        reporter_.error(
            at, fmt::format("this line goes {:.1f} mm below the table {}", -p->point[2], where));
        break;
      case Kind::OutOfReach:
        reporter_.error(
            at, p->needed > p->reach
                    ? fmt::format("this line leaves the arm's reach {} at pitch {:g}deg: the "
                                  "wrist would be {:.0f} mm from the shoulder, {:.0f} mm beyond "
                                  "the {:g} mm the arm spans",
                                  where, std::round(p->pitch * 10) / 10, p->needed,
                                  p->needed - p->reach, p->reach)
                    : fmt::format("this line passes too near the base {} at pitch {:g}deg: the "
                                  "wrist would be {:.0f} mm from the shoulder, nearer than the "
                                  "arm can fold ({:g} mm)",
                                  where, std::round(p->pitch * 10) / 10, p->needed, p->reach));
        break;
      case Kind::JointLimit: {
        const ServoInfo& servo = robot_.info.servos[placed.joints[p->joint]];
        const bool above = p->units > servo.max;
        reporter_.error(
            at,
            fmt::format("this line needs '{}' at {} ({:.1f}deg) {}, {} {} its {} {}", servo.name,
                        p->units, p->angle, where, p->over, above ? "above" : "below",
                        above ? "max" : "min", above ? servo.max : servo.min));
        break;
      }
      case Kind::Rounding:
        reporter_.error(
            at, fmt::format(
                    "rounding the joints to whole units puts the tip at least {:.2f} mm "
                    "from the line's end, {}, more than the tolerance of {:g}mm{}",
                    p->error, point_text(p->point), tolerance_mm,
                    p->suggest > 0
                        ? fmt::format("; give a larger one, e.g. 'tolerance: {:g}mm'", p->suggest)
                        : ""));
        break;
      case Kind::Tolerance:
        reporter_.error(
            at, fmt::format("no actions of at least {}ms keep the tip within {:g}mm of this line "
                            "beyond {}, {} (rounding the joints to whole units moves "
                            "the tip too far){}",
                            lsc::kMinActionMs, tolerance_mm,
                            inside ? fmt::format("{:g}% of it", std::round(p->fraction * 100) + 0.0)
                                   : "where the ease runs " + along,
                            point_text(p->point),
                            p->suggest > 0
                                ? fmt::format("; give a larger tolerance, e.g. 'tolerance: {:g}mm'",
                                              p->suggest)
                                : ""));
        break;
    }
    return false;
  }

  LineRecord record;
  record.start = start;
  record.end = end;
  record.tolerance_units = tolerance_units;
  record.step_at = step.location;
  record.path_at = step.find("path")->location;
  for (std::size_t j = 0; j < 4 + others.size(); ++j) {
    const std::size_t servo = j < 4 ? placed.joints[j] : others[j - 4];
    if (!claim(servo, step.location)) return false;
    record.servos.push_back(servo);
    record.first.push_back(timeline_.count(servo));
  }
  const std::vector<std::vector<Segment>> pieces = line_pieces(request, fit, record);
  for (std::size_t j = 0; j < record.servos.size(); ++j) {
    const std::size_t servo = record.servos[j];
    const Segment* fastest = nullptr;
    for (const Segment& piece : pieces[j]) {
      auto speed = [](const Segment& x) {
        return std::abs(x.to - x.from) / (x.end.value() - x.start.value());
      };
      if (fastest == nullptr || speed(piece) > speed(*fastest)) fastest = &piece;
      add_segment(servo, piece);
    }
    check_kinematics(servo, *fastest, std::nan(""), std::nullopt, findings);
    pos_[servo] = static_cast<int>(pieces[j].back().to);
  }
  record.pieces = fit.actions.size();
  for (const compiler::TipLineAction& a : fit.actions) record.ends.push_back(a.end_ms);
  record.request = std::move(request);
  lines_.push_back(std::move(record));
  record_arm_move([](std::size_t) { return true; }, start, end, step.location, true, tolerance_mm);
  count_actions(fit.actions.size(), step.location);
  timeline_.tip_moves.push_back(
      {start.value(), end.value(), fit.from, placed.point, /*line=*/true});
  return true;
}

std::vector<std::vector<Segment>> ServoLowering::line_pieces(
    const compiler::TipLineRequest& request, const compiler::TipLineResult& fit,
    const LineRecord& line) const {
  // Ordinary straight pieces of every servo of the move, kept as they are (keep_boundaries):
  // the fitter makes each one action, whole units at whole milliseconds, so what runs is what
  // was checked here.
  std::vector<std::vector<Segment>> out(line.servos.size());
  for (std::size_t j = 0; j < line.servos.size(); ++j) {
    auto target = [&](const compiler::TipLineAction& a) {
      return j < 4 ? a.targets[j] : a.others[j - 4];
    };
    double prev = j < 4 ? request.from[j] : request.others[j - 4].from;
    for (std::size_t k = 0; k < fit.actions.size(); ++k) {
      Segment piece;
      piece.kind = CurveKind::Linear;
      piece.keep_boundaries = true;
      piece.start = k == 0 ? line.start : ExactMs::ratio(fit.actions[k - 1].end_ms, 1);
      piece.end = k + 1 == fit.actions.size() ? line.end : ExactMs::ratio(fit.actions[k].end_ms, 1);
      piece.from = prev;
      piece.to = target(fit.actions[k]);
      piece.tolerance = line.tolerance_units;
      piece.at = line.step_at;
      prev = piece.to;
      out[j].push_back(piece);
    }
  }
  return out;
}

void ServoLowering::refit_lines() {
  const std::uint32_t min = lsc::kMinActionMs;
  // Latest first, so that replacing a line's pieces leaves the indices of earlier ones as they
  // were recorded.
  for (auto line = lines_.rbegin(); line != lines_.rend(); ++line) {
    compiler::TipLineRequest& r = line->request;
    // Every other servo's segment boundaries inside the line, rounded as the fitter rounds
    // them, and kept as it keeps knots: one closer than the shortest action after the one
    // before (or after the line's start) is merged into it. One that near the line's end
    // cannot be an action boundary of the line and is left to the fitter.
    std::vector<std::uint32_t> knots;
    // Other servos on a curve during the line, whose segments lie within it: the fitter would
    // cut the joints' pieces wherever it fits them, so the line carries them as its own others
    // (`first` and `count`: their segments it replaces).
    struct Follower {
      std::size_t servo = 0, first = 0, count = 0;
    };
    std::vector<Follower> followers;
    for (std::size_t servo = 0; servo < timeline_.servo_count(); ++servo) {
      if (std::find(line->servos.begin(), line->servos.end(), servo) != line->servos.end()) {
        continue;
      }
      Follower f{servo, timeline_.count(servo), 0};
      bool curved = false, within = true;
      for (std::size_t i = 0; i < timeline_.count(servo); ++i) {
        const std::int64_t a = timeline_.start_of(servo, i).round();
        const std::int64_t b = timeline_.end_of(servo, i).round();
        for (const std::int64_t ms : {a, b}) {
          if (ms > r.start_ms && ms < r.end_ms) knots.push_back(static_cast<std::uint32_t>(ms));
        }
        if (b <= r.start_ms || a >= r.end_ms) continue;
        f.first = std::min(f.first, i);
        ++f.count;
        curved = curved || !timeline_.segment(servo, i).is_straight();
        within = within && a >= r.start_ms && b <= r.end_ms;
      }
      if (curved && within && timeline_.value(servo, r.start_ms)) followers.push_back(f);
    }
    std::sort(knots.begin(), knots.end());
    std::vector<std::uint32_t> forced;
    bool needed = !followers.empty();
    for (const std::uint32_t k : knots) {
      const std::uint32_t before = forced.empty() ? r.start_ms : forced.back();
      if (k - before < min || r.end_ms - k < min) continue;
      forced.push_back(k);
      needed = needed || !std::binary_search(line->ends.begin(), line->ends.end(), k);
    }
    if (!needed) continue;
    r.forced_ms = forced;
    r.end_joints = compiler::Joints{};
    for (std::size_t j = 0; j < 4; ++j) {
      r.end_joints->at(j) = static_cast<int>(
          timeline_.segment(line->servos[j], line->first[j] + line->pieces - 1).to);
    }
    LineRecord all = *line;  // the line's own servos, then the followers
    for (const Follower& f : followers) {
      compiler::OtherServo o;
      o.tolerance = INFINITY;
      for (std::size_t i = f.first; i < f.first + f.count; ++i) {
        o.tolerance = std::min(o.tolerance, timeline_.segment(f.servo, i).tolerance);
      }
      // Its segments from the one in force at the line's start to the one at its end.
      const std::size_t from = timeline_.index_at(f.servo, r.start_ms).value_or(f.first);
      const std::size_t to = timeline_.index_at(f.servo, r.end_ms).value_or(f.first);
      for (std::size_t i = from; i <= to; ++i) o.curve.push_back(timeline_.segment(f.servo, i));
      o.from = *timeline_.value(f.servo, r.start_ms);
      o.to = *timeline_.value(f.servo, r.end_ms);
      r.others.push_back(std::move(o));
      all.servos.push_back(f.servo);
    }
    compiler::TipLineResult fit = compiler::fit_tip_line(r);
    if (fit.problem && !followers.empty()) {
      // The curves cannot share the line's actions within their tolerances: the fitter fits
      // them with actions of its own, as before, and servo_program() warns if the tip then strays.
      r.others.resize(line->servos.size() - 4);
      all.servos.resize(line->servos.size());
      followers.clear();
      fit = compiler::fit_tip_line(r);
    }
    if (fit.problem) continue;  // the pieces stay as they were; servo_program() warns
    std::vector<std::vector<Segment>> pieces = line_pieces(r, fit, all);
    auto speed = [](const Segment& x) {
      return std::abs(x.to - x.from) / (x.end.value() - x.start.value());
    };
    // The new pieces are other straight pieces: one faster than every piece before may break
    // a servo's max_speed where none did. (A limit the first pieces broke was said at the step;
    // saying it twice would not help.)
    std::vector<KinematicFinding> findings;
    for (std::size_t j = 0; j < line->servos.size(); ++j) {
      const std::size_t servo = line->servos[j];
      double before = 0;
      for (std::size_t i = line->first[j]; i < line->first[j] + line->pieces; ++i) {
        before = std::max(before, speed(timeline_.segment(servo, i)));
      }
      const std::optional<double>& limit = robot_.info.servos[servo].max_speed;
      const Segment* fastest = nullptr;
      for (const Segment& piece : pieces[j]) {
        if (fastest == nullptr || speed(piece) > speed(*fastest)) fastest = &piece;
      }
      if (fastest != nullptr && speed(*fastest) > before && limit &&
          before * 1000 <= *limit + 1e-9) {
        check_kinematics(servo, *fastest, std::nan(""), std::nullopt, findings);
      }
      timeline_.replace(servo, line->first[j], line->pieces, pieces[j]);
    }
    report_kinematics(findings);
    for (std::size_t k = 0; k < followers.size(); ++k) {
      const Follower& f = followers[k];
      // Its own tolerance, and the step of its segment in force, for the fitter's accounts and
      // the listing's sources.
      for (Segment& piece : pieces[line->servos.size() + k]) {
        const std::size_t i = std::clamp<std::size_t>(
            timeline_.index_at(f.servo, piece.start.value()).value_or(f.first), f.first,
            f.first + f.count - 1);
        piece.tolerance = r.others[line->servos.size() - 4 + k].tolerance;
        piece.at = timeline_.segment(f.servo, i).at;
      }
      timeline_.replace(f.servo, f.first, f.count, pieces[line->servos.size() + k]);
      ++replaced_curves_;
      timeline_.taken_into_lines.resize(timeline_.servo_count(), false);
      timeline_.taken_into_lines[f.servo] = true;
    }
  }
}

}  // namespace seqc::compiler
