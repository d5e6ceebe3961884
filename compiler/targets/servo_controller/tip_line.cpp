#include "compiler/targets/servo_controller/tip_line.hpp"

#include <algorithm>
#include <cmath>

#include "compiler/fitting/fitter.hpp"
#include "compiler/program/arm_kinematics.hpp"
#include "compiler/targets/servo_controller/arm_ik.hpp"

namespace seqc::compiler {
namespace {

constexpr std::uint32_t kFullGridMs = 600;
constexpr std::uint32_t kGridPoints = 200;
constexpr int kGiveUp = 6;
constexpr std::size_t kCandidates = 6;
constexpr int kRetries = 5;  // doublings of the tolerance tried to suggest one that works
// A line up to kFullCheckMs is checked (table, reach, limits, the measured error) at every
// millisecond; a longer one at about kFullCheckMs evenly spaced instants and its grid points.
constexpr std::uint32_t kFullCheckMs = 60'000;
// An action up to kExactActionMs is checked at every millisecond; a longer one (only in a long
// line, whose tip moves little between them) at kActionChecks evenly spaced instants against
// the tolerance less kSampledMargin of it, so that an action costs the same for any length.
constexpr std::uint32_t kExactActionMs = 2'000;
constexpr std::uint32_t kActionChecks = 128;
constexpr double kSampledMargin = 0.05;

// The instants (ms from the line's start) at which an action from t1 to t2 is checked: every
// one inside, or kActionChecks evenly spaced ones for a long action.
template <typename F>
bool all_inside(std::uint32_t t1, std::uint32_t t2, F&& ok) {
  const std::uint32_t dt = t2 - t1;
  if (dt <= kExactActionMs) {
    for (std::uint32_t t = t1 + 1; t < t2; ++t) {
      if (!ok(t, false)) return false;
    }
    return true;
  }
  for (std::uint32_t i = 1; i < kActionChecks; ++i) {
    const auto t = static_cast<std::uint32_t>(t1 + std::uint64_t{dt} * i / kActionChecks);
    if (!ok(t, true)) return false;
  }
  return true;
}

double distance(const Point& a, const Point& b) {
  return std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
}

Point tip_of(const compiler::ArmGeometry& arm, const std::array<double, 4>& joints) {
  return arm_points(arm, joints).tip;
}

std::array<double, 4> as_double(const Joints& j) {
  return {static_cast<double>(j[0]), static_cast<double>(j[1]), static_cast<double>(j[2]),
          static_cast<double>(j[3])};
}

// The line's point at ms i from its start: the step's easing applied to the distance.
Point line_point(const TipLineRequest& r, const Point& from, std::uint32_t i) {
  const std::uint32_t n = r.end_ms - r.start_ms;
  const double f = n == 0 ? 1.0 : r.ease.at(static_cast<double>(i) / static_cast<double>(n));
  Point p{};
  for (std::size_t k = 0; k < 3; ++k) p[k] = from[k] + (r.to[k] - from[k]) * f;
  return p;
}

class LineSearch {
 public:
  LineSearch(const TipLineRequest& r, Point from, std::vector<std::uint32_t> grid,
             std::vector<std::vector<Joints>> candidates)
      : r_(r), from_(from), grid_(std::move(grid)), cand_(std::move(candidates)) {
    forced_.assign(grid_.size(), 0);
    for (std::size_t g = 0; g < grid_.size(); ++g) {
      forced_[g] = std::binary_search(r_.forced_ms.begin(), r_.forced_ms.end(), grid_[g]) ? 1 : 0;
    }
  }

  // The fewest actions from the first grid point to the last within `tol`; empty when none.
  // `farthest` gets the latest millisecond any chain of actions reached.
  std::vector<TipLineAction> run(double tol, std::uint32_t& farthest) const {
    struct State {
      std::size_t g = 0, c = 0;
    };
    std::vector<std::vector<int>> parent(grid_.size());
    std::vector<std::vector<std::size_t>> parent_c(grid_.size());
    for (std::size_t g = 0; g < grid_.size(); ++g) {
      parent[g].assign(cand_[g].size(), -2);  // -2: not reached
      parent_c[g].assign(cand_[g].size(), 0);
    }
    parent[0][0] = -1;
    farthest = grid_.front();
    std::vector<State> frontier = {{0, 0}};
    const std::size_t last = grid_.size() - 1;
    while (!frontier.empty()) {
      // The latest boundaries first: the end is most likely reached from them, and the search
      // stops at the first chain that reaches it (every chain of this layer has as many actions).
      std::sort(frontier.begin(), frontier.end(),
                [](const State& a, const State& b) { return a.g > b.g; });
      std::vector<State> next;
      for (const State& s : frontier) {
        int fails = 0;
        for (std::size_t g = s.g + 1; g < grid_.size(); ++g) {
          // No action spans a forced boundary: the fitter ends every servo's action there.
          if (g > s.g + 1 && forced_[g - 1] != 0) break;
          const std::uint32_t dt = grid_[g] - grid_[s.g];
          if (dt < r_.min_action_ms) continue;
          if (dt > r_.max_action_ms) break;
          bool any = false, tried = false;
          if (!others_follow(grid_[s.g], grid_[g])) {
            if (++fails >= kGiveUp) break;
            continue;
          }
          for (std::size_t c = 0; c < cand_[g].size(); ++c) {
            if (parent[g][c] != -2) continue;
            tried = true;
            if (!follows(s, g, c, tol)) continue;
            any = true;
            parent[g][c] = static_cast<int>(s.g);
            parent_c[g][c] = s.c;
            farthest = std::max(farthest, grid_[g]);
            if (g == last) return chain(parent, parent_c, g, c);
            next.push_back({g, c});
          }
          if (!tried) continue;
          fails = any ? 0 : fails + 1;
          if (fails >= kGiveUp) break;
        }
      }
      frontier = std::move(next);
    }
    return {};
  }

  // The tip's largest distance from the line over an action, and where.
  double action_error(std::uint32_t t1, const Joints& c1, std::uint32_t t2, const Joints& c2,
                      std::uint32_t& at) const {
    double worst = -1;
    const std::uint32_t stride = t2 - t1 <= kExactActionMs ? 1 : (t2 - t1) / kActionChecks;
    for (std::uint32_t t = t1; t <= t2; t = t == t2 ? t2 + 1 : std::min(t2, t + stride)) {
      const double e = error_at(t1, c1, t2, c2, t);
      if (e > worst) worst = e, at = t;
    }
    return worst;
  }

 private:
  template <typename S>
  bool follows(const S& s, std::size_t g, std::size_t c, double tol) const {
    const std::uint32_t t1 = grid_[s.g], t2 = grid_[g];
    const Joints& c1 = cand_[s.g][s.c];
    const Joints& c2 = cand_[g][c];
    // The middle first: where a joint's straight line strays most from its curve.
    if (error_at(t1, c1, t2, c2, t1 + (t2 - t1) / 2) > tol) return false;
    return all_inside(t1, t2, [&](std::uint32_t t, bool sampled) {
      return error_at(t1, c1, t2, c2, t) <= (sampled ? tol * (1 - kSampledMargin) : tol);
    });
  }

  double error_at(std::uint32_t t1, const Joints& c1, std::uint32_t t2, const Joints& c2,
                  std::uint32_t t) const {
    std::array<double, 4> j{};
    const double f = static_cast<double>(t - t1) / static_cast<double>(t2 - t1);
    for (std::size_t k = 0; k < 4; ++k) {
      j[k] = compiler::controller_output(r_.model, c1[k] + (c2[k] - c1[k]) * f);
    }
    return distance(tip_of(r_.arm, j), line_point(r_, from_, t - r_.start_ms));
  }

  // Whether the other servos stay within their tolerance over an action.
  bool others_follow(std::uint32_t t1, std::uint32_t t2) const {
    for (std::size_t k = 0; k < r_.others.size(); ++k) {
      const double a = other_target(k, t1), b = other_target(k, t2);
      const double tol = r_.others[k].tolerance;
      const bool inside = all_inside(t1, t2, [&](std::uint32_t t, bool sampled) {
        const double f = static_cast<double>(t - t1) / static_cast<double>(t2 - t1);
        const double v = compiler::controller_output(r_.model, a + (b - a) * f);
        return std::abs(v - other_value(k, t)) <= (sampled ? tol * (1 - kSampledMargin) : tol);
      });
      if (!inside) return false;
    }
    return true;
  }

 public:
  double other_value(std::size_t k, std::uint32_t t) const {
    const OtherServo& o = r_.others[k];
    if (!o.curve.empty()) {
      // As Timeline::value(): the last segment starting at or before t.
      const double at = t;
      auto it = std::upper_bound(
          o.curve.begin(), o.curve.end(), at,
          [](double v, const compiler::Segment& s) { return v < s.start.value(); });
      if (it != o.curve.begin()) --it;
      return it->value(at);
    }
    const std::uint32_t n = r_.end_ms - r_.start_ms;
    const double f =
        n == 0 ? 1.0 : r_.ease.at(static_cast<double>(t - r_.start_ms) / static_cast<double>(n));
    return o.from + (o.to - o.from) * f;
  }
  int other_target(std::size_t k, std::uint32_t t) const {
    return static_cast<int>(std::llround(other_value(k, t)));
  }

 private:
  std::vector<TipLineAction> chain(const std::vector<std::vector<int>>& parent,
                                   const std::vector<std::vector<std::size_t>>& parent_c,
                                   std::size_t g, std::size_t c) const {
    std::vector<TipLineAction> out;
    while (parent[g][c] >= 0) {
      TipLineAction a{grid_[g], cand_[g][c], {}};
      for (std::size_t k = 0; k < r_.others.size(); ++k) {
        a.others.push_back(other_target(k, grid_[g]));
      }
      out.push_back(std::move(a));
      const std::size_t pg = static_cast<std::size_t>(parent[g][c]);
      c = parent_c[g][c];
      g = pg;
    }
    std::reverse(out.begin(), out.end());
    return out;
  }

  const TipLineRequest& r_;
  Point from_;  // the line's start
  std::vector<std::uint32_t> grid_;
  std::vector<std::vector<Joints>> cand_;
  std::vector<char> forced_;  // per grid point: a boundary every chain must have
};

}  // namespace

TipLineResult fit_tip_line(const TipLineRequest& r) {
  TipLineResult out;
  const compiler::ArmGeometry& arm = r.arm;
  const compiler::ArmJoint* joints[] = {&arm.base, &arm.shoulder, &arm.elbow, &arm.wrist};
  out.from = tip_of(arm, as_double(r.from));
  const std::uint32_t n = r.end_ms - r.start_ms;

  // The boundaries searched: every millisecond of a short line, an even grid beyond (no
  // coarser than a quarter of the longest action, so that actions join its points).
  std::vector<std::uint32_t> grid;
  std::uint32_t step = n <= kFullGridMs ? 1 : (n + kGridPoints - 1) / kGridPoints;
  step = std::max<std::uint32_t>(1, std::min(step, r.max_action_ms / 4));
  for (std::uint32_t t = r.start_ms; t < r.end_ms; t += step) grid.push_back(t);
  grid.push_back(r.end_ms);
  if (!r.forced_ms.empty()) {
    grid.insert(grid.end(), r.forced_ms.begin(), r.forced_ms.end());
    std::sort(grid.begin(), grid.end());
    grid.erase(std::unique(grid.begin(), grid.end()), grid.end());
  }

  // The instants (ms from the start) the line is checked at for the table, the reach and the
  // limits, with the exact joint positions there: every millisecond of a line up to
  // kFullCheckMs, about kFullCheckMs evenly spaced ones and the grid's beyond.
  std::vector<std::uint32_t> checks;
  if (n <= kFullCheckMs) {
    checks.resize(n + 1);
    for (std::uint32_t i = 0; i <= n; ++i) checks[i] = i;
  } else {
    const std::uint32_t stride = (n + kFullCheckMs - 1) / kFullCheckMs;
    for (std::uint32_t i = 0; i < n; i += stride) checks.push_back(i);
    for (const std::uint32_t t : grid) checks.push_back(t - r.start_ms);
    checks.push_back(n);
    std::sort(checks.begin(), checks.end());
    checks.erase(std::unique(checks.begin(), checks.end()), checks.end());
  }
  std::vector<Point> points(checks.size());
  std::vector<std::array<double, 4>> ideal(checks.size());
  for (std::size_t c = 0; c < checks.size(); ++c) points[c] = line_point(r, out.from, checks[c]);
  // Below the table: the lowest point, where it is worst (an overshooting ease dips past the end).
  const auto lowest = std::min_element(points.begin(), points.end(),
                                       [](const Point& a, const Point& b) { return a[2] < b[2]; });
  if ((*lowest)[2] < 0) {
    const double t = static_cast<double>(checks[static_cast<std::size_t>(lowest - points.begin())]);
    TipLineProblem p;
    p.kind = TipLineProblem::Kind::BelowTable;
    p.fraction = n == 0 ? 1.0 : r.ease.at(t / n);
    p.point = *lowest;
    out.problem = p;
    return out;
  }
  std::optional<TipLineProblem> limit;
  double base = joints[0]->sign * (r.from[0] - joints[0]->zero) * arm.degrees_per_unit;
  for (std::size_t c = 0; c < checks.size(); ++c) {
    const std::uint32_t i = checks[c];
    const double f = n == 0 ? 1.0 : r.ease.at(static_cast<double>(i) / static_cast<double>(n));
    const Point& p = points[c];
    const double pitch = r.pitch_from + (r.pitch_to - r.pitch_from) * f;
    TipLineProblem here;
    here.fraction = f;
    here.point = p;
    here.pitch = pitch;
    const ArmSolution s = solve_arm(arm, p, pitch, r.elbow_up, base);
    if (!s.angles) {
      here.kind = TipLineProblem::Kind::OutOfReach;
      here.needed = s.needed;
      here.reach = s.reach;
      out.problem = here;
      return out;
    }
    base = s.angles->base;
    const double angles[] = {s.angles->base, s.angles->shoulder, s.angles->elbow, s.angles->wrist};
    for (std::size_t k = 0; k < 4; ++k) {
      ideal[c][k] = joints[k]->zero + joints[k]->sign * angles[k] / arm.degrees_per_unit;
      const long long units = std::llround(ideal[c][k]);
      const long long over =
          units > r.max[k] ? units - r.max[k] : (units < r.min[k] ? r.min[k] - units : 0);
      // The first joint to leave its limits, at its worst point along the line.
      if (over > 0 && (!limit || (limit->joint == k && over > limit->over))) {
        here.kind = TipLineProblem::Kind::JointLimit;
        here.joint = k;
        here.units = units;
        here.over = over;
        here.angle = angles[k];
        limit = here;
      }
    }
  }
  if (limit) {
    out.problem = limit;
    return out;
  }
  // Where ms i from the start is among the checked instants (every grid point is).
  auto checked = [&](std::uint32_t i) {
    return static_cast<std::size_t>(std::lower_bound(checks.begin(), checks.end(), i) -
                                    checks.begin());
  };

  // Candidate targets at each boundary, nearest the line first; the start is where the joints are.
  auto candidates = [&](std::uint32_t t, double tol, double* best) {
    const std::size_t i = checked(t - r.start_ms);
    std::vector<std::pair<double, Joints>> found;
    double nearest = INFINITY;
    for (int mask = 0; mask < 16; ++mask) {
      Joints c{};
      bool inside = true;
      for (std::size_t k = 0; k < 4; ++k) {
        const double v = (mask >> k & 1) ? std::ceil(ideal[i][k]) : std::floor(ideal[i][k]);
        c[k] = static_cast<int>(v);
        inside = inside && c[k] >= r.min[k] && c[k] <= r.max[k];
      }
      if (!inside) continue;
      const double e = distance(tip_of(arm, as_double(c)), points[i]);
      nearest = std::min(nearest, e);
      if (e <= tol &&
          std::none_of(found.begin(), found.end(), [&](const auto& f) { return f.second == c; })) {
        found.emplace_back(e, c);
      }
    }
    if (best) *best = nearest;
    std::sort(found.begin(), found.end(),
              [](const auto& a, const auto& b) { return a.first < b.first; });
    if (found.size() > kCandidates) found.resize(kCandidates);
    std::vector<Joints> js;
    for (const auto& f : found) js.push_back(f.second);
    return js;
  };
  auto search = [&](double tol, std::uint32_t& farthest, double* end_error) {
    std::vector<std::vector<Joints>> cand;
    cand.push_back({r.from});
    for (std::size_t g = 1; g < grid.size(); ++g) {
      cand.push_back(candidates(grid[g], tol, g + 1 == grid.size() ? end_error : nullptr));
    }
    if (r.end_joints) cand.back() = {*r.end_joints};
    LineSearch s(r, out.from, grid, std::move(cand));
    return std::pair{s.run(tol, farthest), LineSearch(r, out.from, grid, {})};
  };

  double end_error = 0;
  std::uint32_t farthest = r.start_ms;
  auto [actions, checker] = search(r.tolerance_mm, farthest, &end_error);
  if (actions.empty()) {
    TipLineProblem p;
    const bool rounding = end_error > r.tolerance_mm;
    p.kind = rounding ? TipLineProblem::Kind::Rounding : TipLineProblem::Kind::Tolerance;
    const std::uint32_t at = rounding ? r.end_ms : farthest;
    p.point = line_point(r, out.from, at - r.start_ms);
    p.fraction = n == 0 ? 1.0 : r.ease.at(static_cast<double>(at - r.start_ms) / n);
    p.error = end_error;
    // A tolerance that works: the rounding at the end with a margin, doubled until it does.
    double tol = rounding ? std::ceil(end_error * 2 + 0.5) / 2 : r.tolerance_mm * 2;
    for (int i = 0; i < kRetries; ++i, tol *= 2) {
      std::uint32_t ignored = 0;
      if (!search(tol, ignored, nullptr).first.empty()) {
        p.suggest = tol;
        break;
      }
    }
    out.problem = p;
    return out;
  }
  std::uint32_t t1 = r.start_ms;
  Joints c1 = r.from;
  for (const TipLineAction& a : actions) {
    std::uint32_t at = 0;
    const double e = checker.action_error(t1, c1, a.end_ms, a.targets, at);
    if (e > out.max_error_mm) out.max_error_mm = e, out.max_error_at_ms = at;
    t1 = a.end_ms;
    c1 = a.targets;
  }
  out.actions = std::move(actions);
  return out;
}

TipLineError measure_tip_line(const TipLineRequest& r, const std::array<std::size_t, 4>& joints,
                              const std::vector<compiler::FittedAction>& actions,
                              double board_per_ms) {
  // Per joint, the actions that name it: when each starts, how long it lasts, its target.
  struct Move {
    double start = 0, time = 0;
    int target = 0;
  };
  std::array<std::vector<Move>, 4> moves;
  for (const compiler::FittedAction& a : actions) {
    for (const compiler::FittedTarget& t : a.targets) {
      for (std::size_t k = 0; k < 4; ++k) {
        if (t.servo == joints[k]) {
          moves[k].push_back(
              {static_cast<double>(a.start_ms), static_cast<double>(a.time_ms), t.position});
        }
      }
    }
  }
  auto position = [&](std::size_t k, double t) {
    const std::vector<Move>& m = moves[k];
    // The last action starting before t moves the joint from the one before's target.
    const auto it = std::lower_bound(m.begin(), m.end(), t,
                                     [](const Move& x, double v) { return x.start < v; });
    if (it == m.begin()) return m.empty() ? static_cast<double>(r.from[k]) : m.front().target;
    const Move& now = *(it - 1);
    const double from = it - 1 == m.begin() ? now.target : (it - 2)->target;
    const double f = std::min(1.0, (t - now.start) / now.time);
    return compiler::controller_output(r.model, from + (now.target - from) * f);
  };
  const Point from = tip_of(r.arm, as_double(r.from));
  const std::uint32_t n = r.end_ms - r.start_ms;
  TipLineError out;
  // Every millisecond of a line up to kFullCheckMs, about kFullCheckMs instants of a longer one.
  const std::uint32_t stride = n <= kFullCheckMs ? 1 : (n + kFullCheckMs - 1) / kFullCheckMs;
  for (std::uint32_t i = 0; i <= n; i = i == n ? n + 1 : std::min(n, i + stride)) {
    const Point want = line_point(r, from, i);
    const double t = static_cast<double>(r.start_ms + i) * board_per_ms;
    const std::array<double, 4> j = {position(0, t), position(1, t), position(2, t),
                                     position(3, t)};
    const double e = distance(tip_of(r.arm, j), want);
    if (e > out.mm) out.mm = e, out.at_ms = r.start_ms + i;
  }
  return out;
}

}  // namespace seqc::compiler
