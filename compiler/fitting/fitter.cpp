#include "compiler/fitting/fitter.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

namespace seqc::compiler {
namespace {

// One servo's segments with their boundaries rounded to whole milliseconds.
struct RoundedTrack {
  std::vector<std::int64_t> start, end;
};

class Fitter {
 public:
  Fitter(const Timeline& timeline, const FitOptions& options)
      : tl_(timeline), opt_(options), tracks_(timeline.servo_count()) {
    for (std::size_t s = 0; s < tracks_.size(); ++s) {
      for (std::size_t i = 0; i < tl_.count(s); ++i) {
        tracks_[s].start.push_back(tl_.start_of(s, i).round());
        tracks_[s].end.push_back(tl_.end_of(s, i).round());
      }
    }
  }

  FitResult run() {
    const std::vector<std::int64_t> knots = collect_knots();
    for (std::size_t k = 0; k + 1 < knots.size(); ++k) fit_between(knots[k], knots[k + 1]);
    return std::move(result_);
  }

 private:
  // [first, last) of servo s's segments that overlap the open interval (a, b).
  std::pair<std::size_t, std::size_t> overlapping(std::size_t s, std::int64_t a,
                                                  std::int64_t b) const {
    const RoundedTrack& t = tracks_[s];
    // Segments are in order and do not overlap, so both ends are sorted.
    const std::size_t first =
        static_cast<std::size_t>(std::upper_bound(t.end.begin(), t.end.end(), a) - t.end.begin());
    std::size_t last = first;
    while (last < t.start.size() && t.start[last] < b) ++last;
    return {first, last};
  }

  std::vector<std::int64_t> collect_knots() const {
    std::vector<std::int64_t> all = {0, tl_.end.round()};
    for (const RoundedTrack& t : tracks_) {
      all.insert(all.end(), t.start.begin(), t.start.end());
      all.insert(all.end(), t.end.begin(), t.end.end());
    }
    std::sort(all.begin(), all.end());
    all.erase(std::unique(all.begin(), all.end()), all.end());
    const std::int64_t end = tl_.end.round();
    std::vector<std::int64_t> kept;
    for (std::int64_t k : all) {
      if (k < 0 || k > end) continue;
      if (kept.empty() || k - kept.back() >= opt_.min_action_ms) {
        kept.push_back(k);
      } else if (k == end && kept.size() > 1) {
        kept.back() = end;  // the end is a boundary; drop the knot just before it instead
      }
    }
    return kept;
  }

  // The intended position of servo s at ms t (nullopt: not known yet).
  std::optional<double> intended(std::size_t s, double t) const { return tl_.value(s, t); }

  // The segment of servo s in force at ms t (the last starting at or before it).
  std::optional<Segment> segment_at(std::size_t s, double t) const {
    const auto i = tl_.index_at(s, t);
    if (!i) return std::nullopt;
    return tl_.segment(s, *i);
  }

  int target(std::size_t s, std::int64_t t) const {
    return static_cast<int>(std::lround(intended(s, static_cast<double>(t)).value_or(0)));
  }

  // How far servo s's straight line from a to b (rounded ends) strays from its curve beyond
  // the tolerance, at its worst millisecond (<= 0: within). `worst_at` gets that instant and
  // `worst_error` the distance there.
  double excess(std::size_t s, std::int64_t a, std::int64_t b, std::int64_t* worst_at = nullptr,
                double* worst_error = nullptr, double* worst_tol = nullptr) const {
    const auto from = intended(s, static_cast<double>(a));
    if (!from) return 0;
    const double p0 = std::round(*from);
    const double p1 = target(s, b);
    double most = -1e300;
    for (std::int64_t t = a; t <= b; ++t) {
      const double td = static_cast<double>(t);
      const double line =
          p0 + (p1 - p0) * (td - static_cast<double>(a)) / static_cast<double>(b - a);
      const double want = intended(s, td).value_or(line);
      const std::optional<Segment> seg = segment_at(s, td);
      const double tol = seg ? seg->tolerance : 1.0;
      const double err = std::abs(line - want);
      if (err - tol > most) {
        most = err - tol;
        if (worst_at != nullptr) *worst_at = t;
        if (worst_error != nullptr) *worst_error = err;
        if (worst_tol != nullptr) *worst_tol = tol;
      }
    }
    return most;
  }

  void fit_between(std::int64_t a, std::int64_t b) {
    std::vector<std::size_t> curved;
    for (std::size_t s = 0; s < tracks_.size(); ++s) {
      // Exact as a straight action only when one straight segment spans the whole interval;
      // anything else (a curve, or a boundary inside after knots were merged) is sampled.
      const auto [first, last] = overlapping(s, a, b);
      if (first == last) continue;
      const RoundedTrack& t = tracks_[s];
      const bool straight = last - first == 1 && tl_.segment(s, first).is_straight() &&
                            t.start[first] <= a && t.end[first] >= b;
      if (!straight) curved.push_back(s);
    }
    const std::int64_t min = opt_.min_action_ms;
    const std::int64_t max = opt_.max_action_ms;
    if (curved.empty()) {
      // Straight lines: exact as one action, or equal parts of at most max_action_ms.
      const std::int64_t n = (b - a + max - 1) / max;
      std::int64_t done = a;
      for (std::int64_t k = 1; k <= n; ++k) {
        const std::int64_t until = a + ((b - a) * k + n / 2) / n;
        emit(done, until);
        done = until;
      }
      return;
    }
    std::int64_t cur = a;
    Samples samples = sample(curved, a, b);
    while (cur < b) {
      const Path path = fewest(samples, curved.size(), cur);
      for (std::int64_t e : path.ends) {
        emit(cur, e, &curved);
        cur = e;
      }
      if (path.complete) return;
      if (path.gave_up) break;
      // No actions within tolerance go on from here, so even the shortest misses: say so there
      // (and only there), then search again from its end.
      const std::int64_t e = b - cur < 2 * min ? b : cur + min;
      emit(cur, e, &curved);
      cur = e;
    }
    while (cur < b) {  // too long to search: the farthest reach
      std::int64_t e = farthest(curved, cur, b);
      if (e == 0) e = b - cur < 2 * min ? b : cur + min;  // even the shortest misses: say so
      emit(cur, e, &curved);
      cur = e;
    }
  }

  // What fewest() reads, per servo of `curved` and millisecond of [a, b]: the intended
  // position, its tolerance and its whole-unit target, computed once for the stretch (a search
  // starts again after each shortfall), and the search's own tables, allocated once.
  struct Samples {
    std::int64_t a = 0;
    std::size_t n = 0;  // b - a
    std::vector<double> want, tol, end;
    std::vector<int> best;
    std::vector<std::size_t> from;
  };
  Samples sample(const std::vector<std::size_t>& curved, std::int64_t a, std::int64_t b) const {
    Samples in;
    in.a = a;
    const std::size_t n = in.n = static_cast<std::size_t>(b - a);
    const std::size_t k = curved.size();
    in.want.resize(k * (n + 1));
    in.tol.resize(k * (n + 1));
    in.end.resize(k * (n + 1));
    in.best.resize(n + 1);
    in.from.resize(n + 1);
    for (std::size_t i = 0; i < k; ++i) {
      for (std::size_t t = 0; t <= n; ++t) {
        const double at = static_cast<double>(a + static_cast<std::int64_t>(t));
        const double w = intended(curved[i], at).value_or(0);
        const std::optional<Segment> seg = segment_at(curved[i], at);
        in.want[i * (n + 1) + t] = w;
        in.tol[i * (n + 1) + t] = (seg ? seg->tolerance : 1.0) + 1e-9;
        in.end[i * (n + 1) + t] = std::round(w);
      }
    }
    return in;
  }

  // The fewest actions from `start` to b that keep the k servos sampled in `in` within
  // tolerance at every millisecond, as their end times (b last). Dynamic programming over
  // boundaries on the 1 ms grid: from each reachable start, lines to later ends are tried while
  // the slope windows (see farthest()) stay open. When no such sequence reaches b, the actions
  // reach the farthest boundary any of them reaches (leaving at least min before b), from which
  // none goes on: the shortfall is there, not wherever a greedy reach happens to get stuck.
  // That is quadratic in the worst case (minutes of slow, smooth curve, where every line
  // reaches far): past kFewestBudget candidate ends it gives up, and the caller takes the
  // greedy farthest reach instead -- within tolerance, perhaps an action or two more.
  struct Path {
    std::vector<std::int64_t> ends;
    bool complete = false;  // the last end is b
    bool gave_up = false;   // over budget: no ends
  };
  static constexpr std::size_t kFewestBudget = 2'000'000;
  Path fewest(Samples& in, std::size_t k, std::int64_t start) const {
    const std::size_t n = in.n;
    const std::size_t first = static_cast<std::size_t>(start - in.a);
    const std::vector<double>& want = in.want;
    const std::vector<double>& tol = in.tol;
    const std::vector<double>& end = in.end;
    constexpr int kNone = 1 << 30;
    std::vector<int>& best = in.best;
    std::vector<std::size_t>& from = in.from;
    std::fill(best.begin() + static_cast<std::ptrdiff_t>(first), best.end(), kNone);
    best[first] = 0;
    const std::size_t min = opt_.min_action_ms, max = opt_.max_action_ms;
    std::vector<double> lo(k), hi(k);
    std::size_t work = 0;
    for (std::size_t s = first; s < n; ++s) {
      if (best[s] == kNone || best[s] + 1 >= best[n]) continue;
      std::fill(lo.begin(), lo.end(), -1e300);
      std::fill(hi.begin(), hi.end(), 1e300);
      for (std::size_t e = s + 1; e <= std::min(n, s + max); ++e) {
        if (++work > kFewestBudget) return {{}, false, true};
        const double span = static_cast<double>(e - s);
        if (e - s >= min && best[s] + 1 < best[e]) {
          bool fits = true;
          for (std::size_t i = 0; i < k && fits; ++i) {
            const double slope = (end[i * (n + 1) + e] - end[i * (n + 1) + s]) / span;
            fits = slope >= lo[i] - 1e-12 && slope <= hi[i] + 1e-12;
          }
          if (fits) {
            best[e] = best[s] + 1;
            from[e] = s;
          }
        }
        bool open = true;
        for (std::size_t i = 0; i < k; ++i) {
          const double p0 = end[i * (n + 1) + s];
          const double w = want[i * (n + 1) + e], u = tol[i * (n + 1) + e];
          lo[i] = std::max(lo[i], (w - u - p0) / span);
          hi[i] = std::min(hi[i], (w + u - p0) / span);
          open = open && lo[i] <= hi[i];
        }
        if (!open) break;
      }
    }
    std::size_t reached = n;
    if (best[n] == kNone) {
      reached = first;
      for (std::size_t t = n - std::min(n, min); t > first && reached == first; --t) {
        if (best[t] != kNone) reached = t;
      }
    }
    Path path;
    path.complete = reached == n;
    for (std::size_t t = reached; t > first; t = from[t]) {
      path.ends.push_back(in.a + static_cast<std::int64_t>(t));
    }
    std::reverse(path.ends.begin(), path.ends.end());
    return path;
  }

  // The farthest end e of an action from `a` (within [a + min, min(a + max, b)], leaving 0 or
  // at least min before b) whose straight lines keep every servo in `curved` within tolerance
  // at every millisecond; 0 if there is none. For a fixed start the line to e stays within
  // tolerance at instant t exactly when its slope lies in a window set by t; the windows of
  // all instants so far are intersected as e advances, so each candidate costs O(servos).
  std::int64_t farthest(const std::vector<std::size_t>& curved, std::int64_t a,
                        std::int64_t b) const {
    const std::int64_t min = opt_.min_action_ms;
    const std::int64_t last = std::min<std::int64_t>(a + opt_.max_action_ms, b);
    std::vector<double> p0(curved.size()), lo(curved.size(), -1e300), hi(curved.size(), 1e300);
    for (std::size_t i = 0; i < curved.size(); ++i) {
      p0[i] = std::round(intended(curved[i], static_cast<double>(a)).value_or(0));
    }
    std::int64_t best = 0;
    for (std::int64_t e = a + 1; e <= last; ++e) {
      const double span = static_cast<double>(e - a);
      const bool allowed = e - a >= min && (e == b || b - e >= min);
      bool fits = allowed;
      for (std::size_t i = 0; i < curved.size() && fits; ++i) {
        const double slope = (target(curved[i], e) - p0[i]) / span;
        fits = slope >= lo[i] - 1e-12 && slope <= hi[i] + 1e-12;
      }
      if (fits) best = e;
      bool open = true;  // the instant e bounds every later line
      for (std::size_t i = 0; i < curved.size(); ++i) {
        const double want = intended(curved[i], static_cast<double>(e)).value_or(p0[i]);
        const std::optional<Segment> seg = segment_at(curved[i], static_cast<double>(e));
        const double tol = (seg ? seg->tolerance : 1.0) + 1e-9;
        lo[i] = std::max(lo[i], (want - tol - p0[i]) / span);
        hi[i] = std::min(hi[i], (want + tol - p0[i]) / span);
        open = open && lo[i] <= hi[i];
      }
      if (!open) break;
    }
    return best;
  }

  void emit(std::int64_t s, std::int64_t e, const std::vector<std::size_t>* curved = nullptr) {
    FittedAction action;
    action.start_ms = static_cast<std::uint32_t>(s);
    action.time_ms = static_cast<std::uint32_t>(e - s);
    std::optional<Instant> newest;
    for (std::size_t servo = 0; servo < tracks_.size(); ++servo) {
      const auto [first, last] = overlapping(servo, s, e);
      if (first == last) continue;
      const Segment seg = tl_.segment(servo, last - 1);
      if (!newest || seg.start > *newest) {
        newest = seg.start;
        action.source = seg.at;
      }
      const bool is_curved =
          curved != nullptr && std::find(curved->begin(), curved->end(), servo) != curved->end();
      const RoundedTrack& t = tracks_[servo];
      if (!is_curved && last - first == 1 && t.start[first] <= s && t.end[first] >= e) {
        // One straight segment spans the action (the common case): no search needed, and the
        // error is the rounding at its ends.
        const double from = seg.value(static_cast<double>(s));
        const double to = seg.value(static_cast<double>(e));
        action.targets.push_back({servo, static_cast<int>(std::lround(to))});
        record_error(servo, s, std::abs(std::round(from) - from));
        record_error(servo, e, std::abs(std::round(to) - to));
        continue;
      }
      // The target is where the segment in force during the action has the servo at its end
      // (at a boundary rounded up past a segment's exact end, that segment's own end value).
      action.targets.push_back(
          {servo, static_cast<int>(std::lround(seg.value(static_cast<double>(e))))});
      account(servo, s, e, is_curved);
    }
    if (action.targets.empty()) {
      for (std::size_t servo = 0; servo < tracks_.size(); ++servo) {
        if (intended(servo, static_cast<double>(s))) {
          action.targets.push_back({servo, target(servo, e)});
          if (action.source.file == kNoFile)
            action.source = tl_.segment(servo, tl_.count(servo) - 1).at;
        }
      }
    }
    result_.actions.push_back(std::move(action));
  }

  // Records the action's error for servo s: sampled on curves, at the ends on straight lines
  // (a line against a line is farthest at an end).
  void account(std::size_t s, std::int64_t a, std::int64_t b, bool is_curved) {
    if (!intended(s, static_cast<double>(a))) return;
    std::int64_t at = a;
    double err = 0, tol = 0;
    if (is_curved) {
      const double over = excess(s, a, b, &at, &err, &tol);
      if (over > 1e-9) {
        const std::optional<Segment> seg = segment_at(s, static_cast<double>(at));
        result_.shortfalls.push_back(
            {s, static_cast<std::uint32_t>(at), err, tol, seg ? seg->at : Location{}});
      }
    } else {
      for (std::int64_t t : {a, b}) {
        const double want = *intended(s, static_cast<double>(t));
        const double e = std::abs(std::round(want) - want);
        if (e > err) {
          err = e;
          at = t;
        }
      }
    }
    record_error(s, at, err);
  }

  void record_error(std::size_t servo, std::int64_t at, double err) {
    if (err > result_.max_error) {
      result_.max_error = err;
      result_.max_error_at_ms = static_cast<std::uint32_t>(at);
      result_.max_error_servo = servo;
    }
  }

  const Timeline& tl_;
  FitOptions opt_;
  std::vector<RoundedTrack> tracks_;
  FitResult result_;
};

}  // namespace

FitResult fit_timeline(const Timeline& timeline, const FitOptions& options) {
  return Fitter(timeline, options).run();
}

}  // namespace seqc::compiler
