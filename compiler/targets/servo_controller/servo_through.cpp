// `through`: a smooth curve through waypoints, each reached at its time. Per servo it is a C1
// cubic Hermite curve: zero velocity at the first and last point, and at an interior waypoint k
// the slope (p[k+1] - p[k-1]) / (t[k+1] - t[k-1]), except 0 where p[k] equals p[k-1] or
// p[k+1] (the servo holds between equal waypoints, never swinging past them). A servo a
// waypoint does not name keeps its value from the waypoint before; the curve starts where the
// servos are.
#include <algorithm>
#include <cmath>

#include "compiler/frontend/key_tables.hpp"
#include "compiler/targets/servo_controller/servo_lowering_state.hpp"
#include "protocol/lsc/group_download.hpp"

namespace seqc::compiler {

void ServoLowering::through_step(const YamlNode& step, const YamlNode& waypoints) {
  if (!waypoints.is_sequence() || waypoints.items.empty()) {
    reporter_.error(waypoints.location,
                    "'through' takes a list of waypoints, each '- pose: ...' with a 'time'");
    return;
  }
  std::optional<double> step_tolerance;
  bool ok = true;
  if (const YamlNode* t = step.find("tolerance")) {
    step_tolerance = parse_tolerance(*t);
    ok = step_tolerance.has_value();
  }
  // points[k][servo]: the position at waypoint k (k = 0 is where the servos are now).
  std::vector<std::vector<std::optional<int>>> points = {pos_};
  std::vector<ExactMs> times = {now_};
  std::vector<bool> named(pos_.size(), false);
  for (const YamlNode& wp : waypoints.items) {
    if (!wp.is_map()) {
      reporter_.error(wp.location, "a waypoint is a map such as '{pose: reach, time: 500ms}'");
      ok = false;
      continue;
    }
    reporter_.check_keys(wp, kWaypointKeys, "in a waypoint");
    const YamlNode* pose = wp.find("pose");
    const YamlNode* time = wp.find("time");
    std::vector<std::optional<int>> values = points.back();
    if (pose == nullptr) {
      reporter_.error(wp.location, "this waypoint needs a 'pose' (a pose name or positions)");
      ok = false;
    } else {
      std::vector<PositionEntry> inline_entries;
      std::optional<Reporter::Note> note;
      const auto* entries =
          scopes_.move_entries(*pose, "servo", entries_parser(), inline_entries, note, reporter_);
      std::vector<std::optional<int>> reached = points.back();
      std::vector<double> deg;
      if (entries == nullptr || !resolve_targets(*entries, note, reached, deg)) {
        ok = false;
      } else {
        for (std::size_t s = 0; s < reached.size(); ++s) {
          if (!reached[s]) continue;
          values[s] = reached[s];
          named[s] = true;
        }
      }
    }
    std::optional<ExactMs> dt;
    if (time == nullptr) {
      reporter_.error(wp.location,
                      "this waypoint needs a 'time': how long after the previous one "
                      "it is reached, e.g. 'time: 500ms'");
      ok = false;
    } else if ((dt = exact_time(*time, "'time'")) && dt->round() < lsc::kMinActionMs) {
      reporter_.error(time->location, "time " + std::to_string(dt->round()) +
                                          "ms is below the controller's minimum of 20ms per "
                                          "action");
      ok = false;
    } else if (!dt) {
      ok = false;
    }
    points.push_back(std::move(values));
    times.push_back(times.back() + dt.value_or(ExactMs(lsc::kMinActionMs)));
  }
  for (std::size_t s = 0; s < named.size() && ok; ++s) {
    if (!named[s] || pos_[s]) continue;
    reporter_.error(step.location, "'" + robot_.info.servos[s].name +
                                       "' has no known position before this curve; move it to "
                                       "an absolute position first");
    ok = false;
  }
  if (!ok) return;

  const double tol = step_tolerance.value_or(tolerance());
  const std::size_t n = points.size() - 1;
  std::vector<KinematicFinding> findings;
  for (std::size_t s = 0; s < named.size(); ++s) {
    if (!named[s]) continue;
    if (!claim(s, step.location)) return;
    auto p = [&](std::size_t k) { return static_cast<double>(*points[k][s]); };
    auto t = [&](std::size_t k) { return times[k].value(); };
    auto slope = [&](std::size_t k) {
      // A servo with the same value at two waypoints in a row holds there: a slope at either
      // end of that stretch would carry it past the value and back.
      if (k == 0 || k == n || p(k) == p(k - 1) || p(k) == p(k + 1)) return 0.0;
      return (p(k + 1) - p(k - 1)) / (t(k + 1) - t(k - 1));
    };
    for (std::size_t k = 0; k < n; ++k) {
      Segment seg;
      seg.kind = CurveKind::Hermite;
      seg.start = times[k];
      seg.end = times[k + 1];
      seg.from = p(k);
      seg.to = p(k + 1);
      seg.slope_from = slope(k);
      seg.slope_to = slope(k + 1);
      seg.tolerance = tol;
      seg.at = waypoints.items[k].location;
      if (!check_overshoot(s, seg, seg.at, std::nullopt)) return;
      check_kinematics(s, seg, std::nan(""), std::nullopt, findings);
      add_segment(s, seg);
    }
    pos_[s] = points[n][s];
  }
  record_arm_move([&](std::size_t servo) { return static_cast<bool>(named[servo]); }, times.front(),
                  times.back(), step.location, false, 0);
  report_kinematics(findings);
  count_actions(n, step.location);
  now_ = times.back();
}

}  // namespace seqc::compiler
