#include "compiler/fitting/fitter.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>

namespace seqc::compiler {

double controller_output(ControllerModel model, double line) {
  switch (model) {
    case ControllerModel::StraightLine:
      return line;
    case ControllerModel::Rounds:
      return std::floor(line + 0.5);
    case ControllerModel::Truncates:
      return std::trunc(line);
  }
  return line;
}

namespace {

// One servo's segments with their boundaries rounded to whole milliseconds.
struct RoundedTrack {
  std::vector<std::int64_t> start, end;
};

// A search's cost is counted in slope-window updates; past kWorkBudget a stretch is cut in two
// (see Fitter::fit_range). The budget keeps any one search to some tens of milliseconds.
constexpr std::size_t kWorkBudget = 40'000'000;
// The joint free fit's work is capped at kJointWorkFactor x the on-curve fit's + kJointWorkFloor
// (its units are dearer, a window per start value rather than per servo); past that the search
// is dropped and the on-curve fit kept.
constexpr std::size_t kJointWorkFactor = 2;
// The work the grid is chosen for, per unit of the on-curve fit's (see joint_grid()).
constexpr double kJointGridTarget = 0.75;
// The coarsest grid of boundaries the joint free fit tries (see joint_grid()).
constexpr std::size_t kMaxGrid = 8;
constexpr std::size_t kJointWorkFloor = 20'000;
// End values the free fit tracks per servo and boundary: one 64-bit set.
constexpr int kMaxValues = 64;
// Labels of the free fit kept per boundary when several servos share it (see free_joint()).
constexpr std::size_t kBeamBest = 2;  // with the fewest actions
constexpr std::size_t kBeamNext = 1;  // with one more (a way round dead ends near the end)
constexpr int kNoKey = std::numeric_limits<int>::max() / 2;

// What the searches read, per curved servo and millisecond of a stretch [a, a + n].
struct Stretch {
  std::int64_t a = 0;
  std::size_t n = 0;           // its length in ms
  std::size_t k = 0;           // curved servos
  std::vector<double> want;    // the intended position
  std::vector<double> lo, hi;  // where the straight line may be there (the model applied)
  std::vector<double> tol;
  std::vector<int> pin;                  // the on-curve target: the intended position rounded
  std::vector<int> vlo, vhi;             // free targets: whole units within tolerance and limits
  std::vector<char> pinned;              // at a knot of the servo's own: its target is `pin`
  std::vector<std::uint32_t> next_knot;  // the first knot after each ms (actions end there)
  std::vector<char> is_knot;
  std::size_t at(std::size_t i, std::size_t t) const { return i * (n + 1) + t; }
};

// A sequence of actions from a stretch's `first` ms, as end times (ms from the stretch's start)
// and each curved servo's target there.
struct Path {
  std::vector<std::size_t> ends;
  std::vector<int> values;  // ends.size() x k
  bool complete = false;    // the last end is the part's end
  bool gave_up = false;     // over the work budget: nothing found
  int key = kNoKey;         // 2 x actions, + 1 when the first action moves nothing
  std::size_t reached = 0;  // the last end (first when none)
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
    pos_.resize(tracks_.size());
  }

  FitResult run() {
    const std::vector<std::int64_t> knots = collect_knots();
    std::size_t j = 0;
    while (j + 1 < knots.size()) {
      const std::vector<std::size_t> curved = curved_in(knots[j], knots[j + 1]);
      if (curved.empty()) {
        fit_straight(knots[j], knots[j + 1]);
        ++j;
        continue;
      }
      // A stretch goes on over a knot while the same servos are curved on both sides and one
      // of them is mid-curve there (its own segments go on): that one's target there is free.
      std::size_t end = j + 1;
      while (end + 1 < knots.size() && curved_in(knots[end], knots[end + 1]) == curved &&
             !std::all_of(curved.begin(), curved.end(),
                          [&](std::size_t s) { return has_knot(s, knots[end]); })) {
        ++end;
      }
      const std::vector<std::int64_t> inner(knots.begin() + static_cast<std::ptrdiff_t>(j) + 1,
                                            knots.begin() + static_cast<std::ptrdiff_t>(end) + 1);
      const Stretch in = sample(curved, knots[j], inner);
      fit_stretch(in, curved);
      j = end;
    }
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

  ServoLimits limits(std::size_t s) const {
    return s < opt_.limits.size() ? opt_.limits[s] : ServoLimits{};
  }

  // Where the straight line may pass at an instant where the curve is at `want` with tolerance
  // `tol`, so that what the controller puts out (the model) is within tolerance.
  std::pair<double, double> line_band(double want, double tol) const {
    const double lo = std::ceil(want - tol), hi = std::floor(want + tol);
    switch (opt_.model) {
      case ControllerModel::StraightLine:
        break;
      case ControllerModel::Rounds:  // floor(x + 0.5) in [lo, hi]
        return {lo - 0.5, hi + 0.5 - 1e-7};
      case ControllerModel::Truncates:  // trunc(x) in [lo, hi], positions being non-negative
        return {lo, hi + 1 - 1e-7};
    }
    return {want - tol, want + tol};
  }

  // How far servo s, moving from p0 at a to p1 at b under the model, strays from its curve
  // beyond the tolerance at its worst millisecond (<= 0: within). `worst_at` gets that instant
  // and `worst_error` the distance there.
  double excess(std::size_t s, std::int64_t a, std::int64_t b, double p0, double p1,
                std::int64_t* worst_at = nullptr, double* worst_error = nullptr,
                double* worst_tol = nullptr) const {
    double most = -1e300;
    for (std::int64_t t = a; t <= b; ++t) {
      const double td = static_cast<double>(t);
      const double line = controller_output(
          opt_.model, p0 + (p1 - p0) * (td - static_cast<double>(a)) / static_cast<double>(b - a));
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

  // The servos whose motion over (a, b) is not one straight segment: a curve, or a boundary
  // inside after knots were merged.
  std::vector<std::size_t> curved_in(std::int64_t a, std::int64_t b) const {
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
    return curved;
  }

  // Whether servo s has a segment boundary at knot k (or one merged into it).
  bool has_knot(std::size_t s, std::int64_t k) const {
    const std::int64_t min = opt_.min_action_ms;
    for (const std::vector<std::int64_t>* v : {&tracks_[s].start, &tracks_[s].end}) {
      const auto it = std::lower_bound(v->begin(), v->end(), k - min + 1);
      if (it != v->end() && *it < k + min) return true;
    }
    return false;
  }

  // Straight lines: exact as one action, or equal parts of at most max_action_ms.
  void fit_straight(std::int64_t a, std::int64_t b) {
    const std::int64_t max = opt_.max_action_ms;
    const std::int64_t n = (b - a + max - 1) / max;
    std::int64_t done = a;
    for (std::int64_t k = 1; k <= n; ++k) {
      const std::int64_t until = a + ((b - a) * k + n / 2) / n;
      emit(done, until);
      done = until;
    }
  }

  // The stretch from knot a over the knots `inner` (its end last).
  Stretch sample(const std::vector<std::size_t>& curved, std::int64_t a,
                 const std::vector<std::int64_t>& inner) const {
    const std::int64_t b = inner.back();
    Stretch in;
    in.a = a;
    const std::size_t n = in.n = static_cast<std::size_t>(b - a);
    const std::size_t k = in.k = curved.size();
    for (auto* v : {&in.want, &in.lo, &in.hi, &in.tol}) v->resize(k * (n + 1));
    for (auto* v : {&in.pin, &in.vlo, &in.vhi}) v->resize(k * (n + 1));
    in.pinned.resize(k * (n + 1));
    in.next_knot.resize(n + 1);
    in.is_knot.resize(n + 1);
    std::size_t next = n;
    for (std::size_t t = n + 1; t-- > 0;) {
      in.next_knot[t] = static_cast<std::uint32_t>(next);
      if (std::binary_search(inner.begin(), inner.end(), a + static_cast<std::int64_t>(t))) {
        next = t;
        in.is_knot[t] = 1;
      }
    }
    for (std::int64_t knot : inner) {
      const std::size_t t = static_cast<std::size_t>(knot - a);
      for (std::size_t i = 0; i < k; ++i)
        in.pinned[in.at(i, t)] = has_knot(curved[i], knot) ? 1 : 0;
    }
    for (std::size_t i = 0; i < k; ++i) {
      const ServoLimits lim = limits(curved[i]);
      for (std::size_t t = 0; t <= n; ++t) {
        const double at = static_cast<double>(a + static_cast<std::int64_t>(t));
        const double w = intended(curved[i], at).value_or(0);
        const std::optional<Segment> seg = segment_at(curved[i], at);
        const double tol = (seg ? seg->tolerance : 1.0) + 1e-9;
        const std::size_t x = in.at(i, t);
        in.want[x] = w;
        in.tol[x] = tol;
        std::tie(in.lo[x], in.hi[x]) = line_band(w, tol);
        in.pin[x] = static_cast<int>(std::lround(w));
        // Free targets: whole units within tolerance and limits, at most kMaxValues of them
        // (around the rounded curve) so that each servo's set fits in 64 bits.
        int lo = std::max(static_cast<int>(std::ceil(w - tol)), lim.min);
        int hi = std::min(static_cast<int>(std::floor(w + tol)), lim.max);
        if (hi - lo + 1 > kMaxValues) {
          lo = std::max(lo, in.pin[x] - kMaxValues / 2 + 1);
          hi = std::min(hi, lo + kMaxValues - 1);
        }
        in.vlo[x] = lo;
        in.vhi[x] = hi;
      }
    }
    return in;
  }

  // Fits a stretch. Each search keeps the free fit only when it beats the on-curve one, but where
  // a search stops short (a shortfall) or is cut, the searches after it start from different
  // places; then the whole stretch is fitted on the curve as well, and the fit with fewer
  // shortfalls (then fewer actions) kept.
  void fit_stretch(const Stretch& in, const std::vector<std::size_t>& curved) {
    // As long as the longest action this stretch can hold (a program of straight moves needs
    // none: the table is not allocated for it).
    const std::size_t spans = std::min<std::size_t>(in.n, opt_.max_action_ms) + 1;
    if (inverse_.size() < spans) {
      const std::size_t had = std::max<std::size_t>(inverse_.size(), 1);
      inverse_.resize(spans);
      for (std::size_t d = had; d < spans; ++d) inverse_[d] = 1.0 / static_cast<double>(d);
    }
    if (!opt_.free_end_points) {
      free_ = false;
      fit_range(in, curved, 0, in.n);
      return;
    }
    const FitResult before = result_;
    const std::vector<std::optional<int>> pos_before = pos_;
    restarted_ = false;
    free_ = true;
    fit_range(in, curved, 0, in.n);
    if (!restarted_) return;
    FitResult with_free = std::move(result_);
    std::vector<std::optional<int>> pos_free = std::move(pos_);
    result_ = before;
    pos_ = pos_before;
    free_ = false;
    fit_range(in, curved, 0, in.n);
    free_ = true;
    // Never a miss the on-curve fit avoids: fewer shortfalls first, then fewer actions.
    if (std::make_pair(with_free.shortfalls.size(), with_free.actions.size()) <
        std::make_pair(result_.shortfalls.size(), result_.actions.size())) {
      result_ = std::move(with_free);
      pos_ = std::move(pos_free);
    }
  }

  // Fits [first, last] of the stretch (ms from its start; both ends pinned on the rounded
  // curve): the better of the two searches, shortfalls where neither reaches the end, and a cut
  // in two where a search runs over its budget.
  void fit_range(const Stretch& in, const std::vector<std::size_t>& curved, std::size_t first,
                 std::size_t last) {
    const std::size_t min = opt_.min_action_ms;
    std::size_t cur = first;
    while (cur < last) {
      std::size_t work_on = 0, work_free = 0;
      Path best = on_curve(in, cur, last, work_on);
      if (free_ && !best.gave_up) {
        // The free fit looks only for fewer actions than the on-curve one found.
        const int bound = best.complete ? best.key : kNoKey;
        Path free = in.k == 1 ? free_single(in, cur, last, bound, work_free)
                              : free_joint(in, cur, last, bound, joint_grid(in, cur, last, work_on),
                                           joint_cap(work_on), work_free);
        if (free.gave_up || better(free, best)) best = std::move(free);
      }
      if (best.gave_up) {
        restarted_ = true;
        const std::size_t cut = cut_point(in, cur, last);
        if (cut > cur) {
          fit_range(in, curved, cur, cut);
          fit_range(in, curved, cut, last);
          return;
        }
        best = Path{};  // too short to cut: shortest actions from here (not reached in practice)
        best.reached = cur;
      }
      std::size_t at = cur;
      for (std::size_t j = 0; j < best.ends.size(); ++j) {
        emit_curved(in, curved, at, best.ends[j], &best.values[j * in.k]);
        at = best.ends[j];
      }
      cur = at;
      if (best.complete) return;
      // No actions within tolerance go on from here, so even the shortest misses: say so there
      // (and only there), then search again from its end.
      restarted_ = true;
      const std::size_t knot = std::min<std::size_t>(last, in.next_knot[cur]);
      const std::size_t e = knot - cur < 2 * min ? knot : cur + min;
      std::vector<int> pinned(in.k);
      for (std::size_t i = 0; i < in.k; ++i) pinned[i] = in.pin[in.at(i, e)];
      emit_curved(in, curved, cur, e, pinned.data());
      cur = e;
    }
  }

  // The work the joint free fit may spend after the on-curve fit spent `on`: a few times as
  // much, so that compiling stays within about twice the on-curve fit's time.
  static std::size_t joint_cap(std::size_t on) { return kJointWorkFactor * on + kJointWorkFloor; }

  // The boundaries the joint free fit tries: every grid-th ms (and every knot), the grid as
  // fine as the cap allows. Its work per candidate end is a window per start value, about
  // (the band's width) x the on-curve fit's window per servo.
  std::size_t joint_grid(const Stretch& in, std::size_t first, std::size_t last,
                         std::size_t on) const {
    double width = 0;
    std::size_t samples = 0;
    for (std::size_t i = 0; i < in.k; ++i) {
      for (std::size_t t = first; t <= last; t += 1 + (last - first) / 16) {
        width += std::max(1, in.vhi[in.at(i, t)] - in.vlo[in.at(i, t)] + 1);
        ++samples;
      }
    }
    const double expected = static_cast<double>(on) * width / static_cast<double>(samples);
    const double allowed = kJointGridTarget * static_cast<double>(on) + kJointWorkFloor;
    return std::clamp<std::size_t>(static_cast<std::size_t>(std::ceil(expected / allowed)), 1,
                                   kMaxGrid);
  }

  // Whether path x is better than y: reaching the end first, then further, then by key.
  static bool better(const Path& x, const Path& y) {
    if (x.complete != y.complete) return x.complete;
    if (x.reached != y.reached) return x.reached > y.reached;
    return x.key < y.key;
  }

  // Where to cut [first, last] when it is too long to search: in its middle half, where the
  // curved servos move least and lie nearest whole units (relative to their tolerances), or at
  // a knot inside, at least min from the knots around it (first if there is no such place).
  std::size_t cut_point(const Stretch& in, std::size_t first, std::size_t last) const {
    const std::size_t min = opt_.min_action_ms;
    if (last - first < 4 * min) return first;
    const std::size_t from = first + (last - first) / 4, to = last - (last - first) / 4;
    std::size_t best = first, since_knot = min;
    double best_score = 1e300;
    for (std::size_t t = first + 1; t < last; ++t) {
      since_knot = in.is_knot[t - 1] != 0 ? 1 : since_knot + 1;
      if (in.is_knot[t] != 0 && best_score > 0) {
        best = t;  // a knot is as good a cut as any
        best_score = 0;
      }
      if (t < from || t > to || since_knot < min || in.next_knot[t] - t < min) continue;
      double score = 0;
      for (std::size_t i = 0; i < in.k; ++i) {
        const double w = in.want[in.at(i, t)];
        const double moves = std::abs(in.want[in.at(i, t + 1)] - in.want[in.at(i, t - 1)]) / 2;
        score += (moves + std::abs(w - std::round(w))) / in.tol[in.at(i, t)];
      }
      if (score < best_score) {
        best_score = score;
        best = t;
      }
    }
    return best;
  }

  // The on-curve fit: the fewest actions from `first` to `last` whose targets are the rounded
  // curve, keeping every servo within tolerance at every millisecond. Dynamic programming over
  // boundaries on the 1 ms grid: from each reachable start, lines to later ends are tried while
  // the slope windows stay open (for a fixed start, the line to e is within the band at instant
  // t exactly when its slope lies in a window set by t; intersecting the windows of all
  // instants so far makes each candidate O(servos)). When no sequence reaches `last`, the
  // actions reach the farthest boundary any of them reaches (leaving at least min before it),
  // from which none goes on: the shortfall is there.
  Path on_curve(const Stretch& in, std::size_t first, std::size_t last, std::size_t& work) const {
    const std::size_t k = in.k;
    const std::size_t min = opt_.min_action_ms, max = opt_.max_action_ms;
    std::vector<int> best(last - first + 1, kNoKey);
    std::vector<std::size_t> from(last - first + 1);
    auto B = [&](std::size_t t) -> int& { return best[t - first]; };
    B(first) = 0;
    std::vector<double> lo(k), hi(k);
    for (std::size_t s = first; s < last; ++s) {
      if (B(s) == kNoKey || B(s) + 2 >= B(last)) continue;
      std::fill(lo.begin(), lo.end(), -1e300);
      std::fill(hi.begin(), hi.end(), 1e300);
      const std::size_t stop = std::min({last, s + max, std::size_t{in.next_knot[s]}});
      for (std::size_t e = s + 1; e <= stop; ++e) {
        work += k;
        if (work > kWorkBudget) return gave_up();
        const double span = static_cast<double>(e - s);
        if (e - s >= min && B(s) + 2 < B(e)) {
          bool fits = true, moves = false;
          for (std::size_t i = 0; i < k && fits; ++i) {
            const int p0 = in.pin[in.at(i, s)], p1 = in.pin[in.at(i, e)];
            const double slope = (p1 - p0) / span;
            fits = slope >= lo[i] - 1e-12 && slope <= hi[i] + 1e-12;
            moves = moves || p1 != p0;
          }
          const int key = B(s) + 2 + (s == first && !moves ? 1 : 0);
          if (fits && key < B(e)) {
            B(e) = key;
            from[e - first] = s;
          }
        }
        bool open = true;
        for (std::size_t i = 0; i < k; ++i) {
          const double p0 = in.pin[in.at(i, s)];
          const std::size_t x = in.at(i, e);
          lo[i] = std::max(lo[i], (in.lo[x] - p0) / span);
          hi[i] = std::min(hi[i], (in.hi[x] - p0) / span);
          open = open && lo[i] <= hi[i];
        }
        if (!open) break;
      }
    }
    std::size_t reached = last;
    if (B(last) == kNoKey) reached = farthest_reached(in, best, first, last);
    Path path;
    path.complete = reached == last;
    path.reached = reached;
    path.key = B(reached) + (path.complete ? 0 : 4 * static_cast<int>(last - reached));
    for (std::size_t t = reached; t > first; t = from[t - first]) path.ends.push_back(t);
    std::reverse(path.ends.begin(), path.ends.end());
    for (std::size_t t : path.ends) {
      for (std::size_t i = 0; i < k; ++i) path.values.push_back(in.pin[in.at(i, t)]);
    }
    return path;
  }

  static Path gave_up() {
    Path p;
    p.gave_up = true;
    return p;
  }

  // The farthest boundary with a finite key, leaving at least min before `last` and before
  // the next knot (first if none).
  std::size_t farthest_reached(const Stretch& in, const std::vector<int>& best, std::size_t first,
                               std::size_t last) const {
    const std::size_t min = opt_.min_action_ms;
    for (std::size_t t = last - std::min(last - first, min); t > first; --t) {
      if (best[t - first] != kNoKey && (in.is_knot[t] != 0 || in.next_knot[t] - t >= min)) {
        return t;
      }
    }
    return first;
  }

  // The free targets of servo i at ms t of the stretch as [low, high] (the pinned value at the
  // part's end).
  std::pair<int, int> free_band(const Stretch& in, std::size_t i, std::size_t t,
                                std::size_t last) const {
    const std::size_t x = in.at(i, t);
    if (t == last || in.pinned[x] != 0) return {in.pin[x], in.pin[x]};
    return {in.vlo[x], in.vhi[x]};
  }

  // The set (bits from `low`) of whole units v in [low, high] with u + lo * span <= v <=
  // u + hi * span: the targets a line from u reaches inside its slope window.
  static std::uint64_t reachable(int u, double lo, double hi, double span, int low, int high) {
    // Clamped to the band first, so that the whole-unit bounds fit an int (and are found
    // without a library call: this runs for every start at every candidate end).
    const double a = std::clamp(u + lo * span - 1e-9, low - 1.0, high + 1.0);
    const double b = std::clamp(u + hi * span + 1e-9, low - 1.0, high + 1.0);
    int from = static_cast<int>(a), to = static_cast<int>(b);
    from += from < a ? 1 : 0;  // ceil
    to -= to > b ? 1 : 0;      // floor
    from = std::max(from, low);
    to = std::min(to, high);
    if (from > to) return 0;
    const int width = to - from + 1;
    const std::uint64_t bits = width >= 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << width) - 1;
    return bits << (from - low);
  }

  // The free fit for one curved servo, exact: the fewest actions to reach each whole unit v at
  // each ms t (within tolerance, inside the limits), from every reachable (s, u) along every
  // line that stays within the band at every millisecond between. Only fits with a key below
  // `bound` (the on-curve fit's) are looked for.
  Path free_single(const Stretch& in, std::size_t first, std::size_t last, int bound,
                   std::size_t& work) const {
    const std::size_t min = opt_.min_action_ms, max = opt_.max_action_ms;
    const std::size_t len = last - first + 1;
    constexpr std::size_t W = kMaxValues;
    std::vector<int> key(len * W, kNoKey);
    std::vector<std::uint32_t> from_t(len * W);
    std::vector<std::uint8_t> from_v(len * W);
    auto K = [&](std::size_t t, int j) -> int& {
      return key[(t - first) * W + static_cast<std::size_t>(j)];
    };
    // The start is pinned: index 0 of a band holding that value alone.
    std::vector<int> low(len), high(len);
    for (std::size_t t = first; t <= last; ++t) {
      std::tie(low[t - first], high[t - first]) = free_band(in, 0, t, last);
    }
    low[0] = high[0] = in.pin[in.at(0, first)];
    K(first, 0) = 0;
    std::vector<int> best_at(len, kNoKey);   // the smallest key at each t
    std::vector<int> worst_at(len, kNoKey);  // the largest
    best_at[0] = 0;
    const std::vector<double>& inv = inverse_spans();
    int u[W], uj[W], uk[W];
    double lo[W], hi[W];
    for (std::size_t s = first; s < last; ++s) {
      const int ls = low[s - first], hs = high[s - first];
      const int limit = std::min(bound, K(last, 0));
      int n = 0;
      for (int v = ls; v <= hs; ++v) {
        const int k = K(s, v - ls);
        if (k == kNoKey || k + 2 >= limit) continue;
        u[n] = v;
        uj[n] = v - ls;
        uk[n] = k;
        lo[n] = -1e300;
        hi[n] = 1e300;
        ++n;
      }
      if (n == 0) continue;
      const std::size_t stop = std::min({last, s + max, std::size_t{in.next_knot[s]}});
      for (std::size_t e = s + 1; e <= stop; ++e) {
        work += static_cast<std::size_t>(n);
        if (work > kWorkBudget) return gave_up();
        const double span = static_cast<double>(e - s), r = inv[e - s];
        const int le = low[e - first], he = high[e - first];
        if (e - s >= min && le <= he) {
          for (int o = 0; o < n; ++o) {
            // Most candidates arrive where every value already has as few actions.
            if (uk[o] + 2 >= worst_at[e - first]) continue;
            std::uint64_t bits = reachable(u[o], lo[o], hi[o], span, le, he);
            while (bits != 0) {
              const int j = std::countr_zero(bits);
              bits &= bits - 1;
              const int k = uk[o] + 2 + (s == first && le + j == u[o] ? 1 : 0);
              if (k < K(e, j)) {
                K(e, j) = k;
                from_t[(e - first) * W + static_cast<std::size_t>(j)] =
                    static_cast<std::uint32_t>(s);
                from_v[(e - first) * W + static_cast<std::size_t>(j)] =
                    static_cast<std::uint8_t>(uj[o]);
                best_at[e - first] = std::min(best_at[e - first], k);
              }
            }
            int worst = 0;
            for (int c = 0; c <= he - le; ++c) worst = std::max(worst, K(e, c));
            worst_at[e - first] = worst;
          }
        }
        const std::size_t x = in.at(0, e);
        const double bl = in.lo[x], bh = in.hi[x];
        bool open = false;
        for (int o = 0; o < n; ++o) {
          lo[o] = std::max(lo[o], (bl - u[o]) * r);
          hi[o] = std::min(hi[o], (bh - u[o]) * r);
          open = open || lo[o] <= hi[o];
        }
        if (!open) break;
      }
    }
    Path path;
    std::size_t t = last;
    int j = 0;
    if (K(last, 0) == kNoKey) {
      if (bound != kNoKey) return path;  // nothing better than the on-curve fit
      t = farthest_reached(in, best_at, first, last);
      // At the farthest boundary, the value with the fewest actions, nearest the curve.
      for (int c = 0; c <= high[t - first] - low[t - first]; ++c) {
        const double w = in.want[in.at(0, t)];
        if (K(t, c) < K(t, j) || (K(t, c) == K(t, j) && std::abs(low[t - first] + c - w) <
                                                            std::abs(low[t - first] + j - w))) {
          j = c;
        }
      }
    }
    path.complete = t == last;
    path.reached = t;
    path.key = t == first ? 0 : K(t, j);
    if (!path.complete) path.key += 4 * static_cast<int>(last - t);
    std::vector<std::pair<std::size_t, int>> back;
    while (t > first) {
      back.push_back({t, low[t - first] + j});
      const std::size_t i = (t - first) * W + static_cast<std::size_t>(j);
      t = from_t[i];
      j = from_v[i];
    }
    std::reverse(back.begin(), back.end());
    for (const auto& [end, value] : back) {
      path.ends.push_back(end);
      path.values.push_back(value);
    }
    return path;
  }

  // 1 / d for every action length d, so that the searches multiply instead of divide.
  const std::vector<double>& inverse_spans() const { return inverse_; }

  // The free fit for several curved servos sharing boundaries. Their joint states are too
  // many to search exactly ((2 x tolerance + 1)^servos per ms), so a label at a boundary holds,
  // per servo, the SET of whole units it can reach there along one sequence of boundaries (the
  // servos' lines are independent once the boundaries are fixed, so the sets are exact for that
  // sequence). A boundary keeps a few labels that no other dominates (as few actions and every
  // set as large): kBeamBest with its fewest actions and kBeamNext with one more, which gets
  // round dead ends where the fewest-action labels' sets cannot go on. Only fits with a key
  // below `bound` (the on-curve fit's) are looked for.
  struct Label {
    int key = kNoKey;
    std::size_t parent = 0;  // label index
    int width = 0;           // the sizes of the sets, summed
    std::size_t t = 0;       // its boundary (ms from the stretch's start)
  };
  Path free_joint(const Stretch& in, std::size_t first, std::size_t last, int bound,
                  std::size_t grid, std::size_t cap, std::size_t& work) const {
    const std::size_t k = in.k;
    const std::size_t min = opt_.min_action_ms, max = opt_.max_action_ms;
    const std::size_t len = last - first + 1;
    std::vector<Label> labels;
    std::vector<std::uint64_t> sets;  // k per label, bits from each servo's low end at its t
    std::vector<std::vector<std::size_t>> at(len);
    std::vector<int> best_count(len, kNoKey);
    std::vector<int> low(len * k), high(len * k);
    for (std::size_t t = first; t <= last; ++t) {
      for (std::size_t i = 0; i < k; ++i) {
        std::tie(low[(t - first) * k + i], high[(t - first) * k + i]) = free_band(in, i, t, last);
      }
    }
    for (std::size_t i = 0; i < k; ++i) low[i] = high[i] = in.pin[in.at(i, first)];
    labels.push_back({0, 0, static_cast<int>(k), first});
    sets.insert(sets.end(), k, 1);
    at[0].push_back(0);
    best_count[0] = 0;
    int best_end = kNoKey;  // the smallest key at `last`
    // Per boundary: how wide a label holding every target of every servo is, and the smallest
    // key of such a label there (no later label with a key as large can enter).
    std::vector<int> full_width(len, 0), full_key(len, kNoKey);
    for (std::size_t t = 0; t < len; ++t) {
      for (std::size_t i = 0; i < k; ++i) {
        full_width[t] += std::max(0, high[t * k + i] - low[t * k + i] + 1);
      }
    }

    // Adds a label at e unless one there dominates it; drops those it dominates; keeps the beam.
    std::vector<std::uint64_t> cand(k);
    auto covers = [&](const std::uint64_t* x, const std::uint64_t* y) {
      for (std::size_t i = 0; i < k; ++i) {
        if ((x[i] & y[i]) != y[i]) return false;
      }
      return true;
    };
    // Labels dropped from a boundary before it was expanded have no children: their slots are
    // used again.
    std::vector<std::size_t> spare;
    auto drop = [&](std::size_t id) { spare.push_back(id); };
    auto insert = [&](std::size_t e, int key, std::size_t parent) {
      const int count = key / 2;
      int& best = best_count[e - first];
      if (best != kNoKey && count > best + 1) return;
      std::vector<std::size_t>& here = at[e - first];
      int width = 0;
      for (std::uint64_t c : cand) width += std::popcount(c);
      // Not taken when one there dominates it, or when its count's beam is full of labels no
      // worse than it.
      std::size_t same_level = 0;
      bool beats_one = false;
      for (std::size_t id : here) {
        const Label& l = labels[id];
        if (l.key <= key && covers(&sets[id * k], cand.data())) return;
        if (l.key / 2 != count) continue;
        ++same_level;
        beats_one = beats_one || key < l.key || (key == l.key && width > l.width) ||
                    covers(cand.data(), &sets[id * k]);
      }
      const int level_best = best == kNoKey ? count : std::min(best, count);
      const std::size_t keep = count == level_best ? kBeamBest : kBeamNext;
      if (same_level >= keep && !beats_one) return;
      std::erase_if(here, [&](std::size_t id) {
        const bool dominated = key <= labels[id].key && covers(cand.data(), &sets[id * k]);
        if (dominated) drop(id);
        return dominated;
      });
      if (width == full_width[e - first]) full_key[e - first] = std::min(full_key[e - first], key);
      std::size_t id = labels.size();
      if (!spare.empty()) {
        id = spare.back();
        spare.pop_back();
        labels[id] = {key, parent, width, e};
        std::copy(cand.begin(), cand.end(), sets.begin() + static_cast<std::ptrdiff_t>(id * k));
      } else {
        labels.push_back({key, parent, width, e});
        sets.insert(sets.end(), cand.begin(), cand.end());
      }
      here.push_back(id);
      best = std::min(best, count);
      if (e == last) best_end = std::min(best_end, key);
      // The beam: at each of the two counts, the labels with the smallest keys, widest first.
      std::erase_if(here, [&](std::size_t x) {
        const bool out = labels[x].key / 2 > best + 1;
        if (out) drop(x);
        return out;
      });
      for (int level : {best, best + 1}) {
        const std::size_t level_keep = level == best ? kBeamBest : kBeamNext;
        for (;;) {
          std::size_t count_here = 0, worst = 0;
          for (std::size_t x : here) {
            if (labels[x].key / 2 != level) continue;
            if (count_here++ == 0 || labels[x].key > labels[worst].key ||
                (labels[x].key == labels[worst].key && labels[x].width < labels[worst].width)) {
              worst = x;
            }
          }
          if (count_here <= level_keep) break;
          std::erase(here, worst);
          drop(worst);
        }
      }
    };

    // The windows of one expansion: one per servo and start value in any label at s.
    // Laid out per servo (index base[i] + bit), so that the window updates run in straight
    // loops: they are most of the search's time.
    std::vector<double> su, slo, shi;
    std::vector<std::size_t> soff;           // where each start's servo's samples begin
    std::vector<std::uint64_t> sreach;       // the targets each reaches at the current end
    std::vector<std::size_t> base(k + 1);    // each servo's first start
    std::vector<std::uint64_t> open_set(k);  // each servo's starts still open, by bit
    const std::vector<double>& inv = inverse_spans();
    std::vector<std::size_t> live;
    auto on_grid = [&](std::size_t t) {
      return grid == 1 || (t - first) % grid == 0 || t == last || in.is_knot[t] != 0;
    };
    for (std::size_t s = first; s < last; ++s) {
      live.clear();
      const int limit = std::min(bound, best_end);
      for (std::size_t id : at[s - first]) {
        if (labels[id].key + 2 < limit) live.push_back(id);
      }
      if (live.empty() || !on_grid(s)) continue;
      su.clear();
      soff.clear();
      slo.clear();
      shi.clear();
      for (std::size_t i = 0; i < k; ++i) {
        std::uint64_t all = 0;
        for (std::size_t id : live) all |= sets[id * k + i];
        base[i] = su.size();
        const int ls = low[(s - first) * k + i];
        for (int b = 0; b < 64; ++b) {
          // Every bit up to the highest is given a start, so that a start's index is its bit.
          if ((all >> b) == 0) break;
          su.push_back(ls + b);
          soff.push_back(in.at(i, 0));
          slo.push_back(-1e300);
          shi.push_back((all >> b & 1) != 0 ? 1e300 : -1e301);
        }
      }
      base[k] = su.size();
      sreach.resize(su.size());
      std::size_t open_count = 0;
      for (std::size_t j = 0; j < su.size(); ++j) open_count += slo[j] <= shi[j] ? 1 : 0;
      const std::size_t stop = std::min({last, s + max, std::size_t{in.next_knot[s]}});
      for (std::size_t e = s + 1; e <= stop; ++e) {
        work += su.size();
        if (work > cap) return Path{};  // dearer than the time it may save: on-curve stays
        const double span = static_cast<double>(e - s), r = inv[e - s];
        // A label with one action more than the fewest only helps near the end, where the
        // shortest action's floor leaves dead ends.
        const int be = best_count[e - first];
        const int slack = last - e < 3 * min ? 1 : 0;
        auto wanted = [&](int key) {
          return (be == kNoKey || key / 2 + 1 <= be + slack) && key + 2 < full_key[e - first];
        };
        if (e - s >= min && on_grid(e)) {
          bool any = false;
          for (std::size_t id : live) any = any || wanted(labels[id].key);
          if (any) {
            for (std::size_t i = 0; i < k; ++i) {
              const std::size_t x = (e - first) * k + i;
              for (std::size_t j = base[i]; j < base[i + 1]; ++j) {
                sreach[j] = slo[j] <= shi[j] ? reachable(static_cast<int>(su[j]), slo[j], shi[j],
                                                         span, low[x], high[x])
                                             : 0;
              }
            }
            for (std::size_t id : live) {
              const int key = labels[id].key;
              if (!wanted(key)) continue;
              bool all = true;
              for (std::size_t i = 0; i < k && all; ++i) {
                std::uint64_t c = 0;
                for (std::uint64_t bits = sets[id * k + i]; bits != 0; bits &= bits - 1) {
                  c |= sreach[base[i] + static_cast<std::size_t>(std::countr_zero(bits))];
                }
                cand[i] = c;
                all = c != 0;
              }
              if (!all) continue;
              if (s != first) {
                insert(e, key + 2, id);
                continue;
              }
              // A first action that moves nothing costs a half more: offer the label without
              // the non-moving choice of the servo that can move most, and the whole label at
              // the higher key when every servo can stay.
              std::size_t widest = k;
              int most = 0;
              bool all_still = true;
              for (std::size_t i = 0; i < k; ++i) {
                const int p = low[i], ls = low[(e - first) * k + i];
                const std::uint64_t still =
                    p >= ls && p - ls < 64 ? std::uint64_t{1} << (p - ls) : 0;
                const int moving = std::popcount(cand[i] & ~still);
                if (moving > most) {
                  most = moving;
                  widest = i;
                }
                all_still = all_still && (cand[i] & still) != 0;
              }
              const std::vector<std::uint64_t> whole = cand;
              if (widest < k) {
                const int p = low[widest], ls = low[(e - first) * k + widest];
                if (p >= ls && p - ls < 64) cand[widest] &= ~(std::uint64_t{1} << (p - ls));
                insert(e, key + 2, id);
              }
              if (all_still) {
                cand = whole;
                insert(e, key + 3, id);
              }
            }
          }
        }
        std::size_t still_open = 0;
        for (std::size_t j = 0; j < su.size(); ++j) {
          const std::size_t x = soff[j] + e;
          slo[j] = std::max(slo[j], (in.lo[x] - su[j]) * r);
          shi[j] = std::min(shi[j], (in.hi[x] - su[j]) * r);
          still_open += slo[j] <= shi[j] ? 1 : 0;
        }
        if (still_open == open_count) continue;
        open_count = still_open;
        for (std::size_t i = 0; i < k; ++i) {
          std::uint64_t open = 0;
          for (std::size_t j = base[i]; j < base[i + 1]; ++j) {
            open |= static_cast<std::uint64_t>(slo[j] <= shi[j]) << (j - base[i]);
          }
          open_set[i] = open;
        }
        // A label goes on while each of its servos has a start still open.
        std::erase_if(live, [&](std::size_t id) {
          for (std::size_t i = 0; i < k; ++i) {
            if ((sets[id * k + i] & open_set[i]) == 0) return true;
          }
          return false;
        });
        if (live.empty()) break;
      }
    }
    // The end: the label with the fewest actions at `last`, or at the farthest boundary.
    std::size_t t = last;
    if (at[last - first].empty()) {
      if (bound != kNoKey) return Path{};  // nothing better than the on-curve fit
      std::vector<int> reached(len, kNoKey);
      for (std::size_t x = 0; x < len; ++x) {
        if (!at[x].empty()) reached[x] = 0;
      }
      t = farthest_reached(in, reached, first, last);
    }
    Path path;
    path.complete = t == last;
    path.reached = t;
    if (t == first) {
      path.key = 4 * static_cast<int>(last - first);
      return path;
    }
    std::size_t id = at[t - first].front();
    for (std::size_t x : at[t - first]) {
      if (labels[x].key < labels[id].key) id = x;
    }
    path.key = labels[id].key + (path.complete ? 0 : 4 * static_cast<int>(last - t));
    // Back from the end: each servo's target there (nearest the curve), then at each earlier
    // boundary a value of the parent's set from which the line to the later target fits.
    std::vector<std::size_t> chain;
    for (std::size_t x = id; x != 0; x = labels[x].parent) chain.push_back(x);
    std::vector<int> later(k);
    for (std::size_t i = 0; i < k; ++i) {
      later[i] = nearest(in, i, t, sets[id * k + i], low[(t - first) * k + i]);
    }
    path.ends.resize(chain.size());
    path.values.resize(chain.size() * k);
    for (std::size_t c = 0; c < chain.size(); ++c) {
      const std::size_t pos = chain.size() - 1 - c;
      const std::size_t e = labels[chain[c]].t, parent = labels[chain[c]].parent;
      const std::size_t s = labels[parent].t;
      path.ends[pos] = e;
      std::copy(later.begin(), later.end(),
                path.values.begin() + static_cast<std::ptrdiff_t>(pos * k));
      for (std::size_t i = 0; i < k; ++i) {
        const int ls = low[(s - first) * k + i];
        int pick = ls;
        double pick_over = 1e300, pick_off = 1e300;
        for (std::uint64_t bits = sets[parent * k + i]; bits != 0; bits &= bits - 1) {
          const int u = ls + std::countr_zero(bits);
          const double over = line_over(in, i, s, e, u, later[i]);
          const double off = std::abs(u - in.want[in.at(i, s)]);
          if (std::max(over, 0.0) < std::max(pick_over, 0.0) ||
              (std::max(over, 0.0) == std::max(pick_over, 0.0) && off < pick_off)) {
            pick = u;
            pick_over = over;
            pick_off = off;
          }
        }
        later[i] = pick;
      }
    }
    return path;
  }

  // The value of `set` (bits from `low`) nearest servo i's curve at t.
  static int nearest(const Stretch& in, std::size_t i, std::size_t t, std::uint64_t set, int low) {
    int pick = low;
    double off = 1e300;
    for (std::uint64_t bits = set; bits != 0; bits &= bits - 1) {
      const int v = low + std::countr_zero(bits);
      const double d = std::abs(v - in.want[in.at(i, t)]);
      if (d < off) {
        off = d;
        pick = v;
      }
    }
    return pick;
  }

  // How far the line from u at s to v at e leaves servo i's band between them (<= 0: never).
  static double line_over(const Stretch& in, std::size_t i, std::size_t s, std::size_t e, int u,
                          int v) {
    double most = -1e300;
    const double span = static_cast<double>(e - s);
    for (std::size_t t = s + 1; t < e; ++t) {
      const double line = u + (v - u) * static_cast<double>(t - s) / span;
      const std::size_t x = in.at(i, t);
      most = std::max({most, in.lo[x] - line, line - in.hi[x]});
    }
    return most;
  }

  // Emits an action of the stretch from ms s to e (from its start), with the curved servos'
  // targets in `values` (the knot's own rule at the stretch's end).
  void emit_curved(const Stretch& in, const std::vector<std::size_t>& curved, std::size_t s,
                   std::size_t e, const int* values) {
    std::vector<std::optional<int>> free(tracks_.size());
    for (std::size_t i = 0; i < in.k && e < in.n; ++i) {
      if (in.pinned[in.at(i, e)] == 0) free[curved[i]] = values[i];
    }
    emit(in.a + static_cast<std::int64_t>(s), in.a + static_cast<std::int64_t>(e), &curved, &free);
  }

  void emit(std::int64_t s, std::int64_t e, const std::vector<std::size_t>* curved = nullptr,
            const std::vector<std::optional<int>>* free = nullptr) {
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
        const int target_to = static_cast<int>(std::lround(to));
        action.targets.push_back({servo, target_to});
        record_error(servo, s, std::abs(std::round(from) - from));
        record_error(servo, e, std::abs(std::round(to) - to));
        pos_[servo] = target_to;
        continue;
      }
      // The target is the free fit's where it chose one; otherwise where the segment in force
      // during the action has the servo at its end (at a boundary rounded up past a segment's
      // exact end, that segment's own end value).
      const int to = free != nullptr && (*free)[servo]
                         ? *(*free)[servo]
                         : static_cast<int>(std::lround(seg.value(static_cast<double>(e))));
      action.targets.push_back({servo, to});
      account(servo, s, e, to, is_curved);
      pos_[servo] = to;
    }
    if (action.targets.empty()) {
      for (std::size_t servo = 0; servo < tracks_.size(); ++servo) {
        if (intended(servo, static_cast<double>(s))) {
          action.targets.push_back({servo, target(servo, e)});
          pos_[servo] = target(servo, e);
          if (action.source.file == kNoFile)
            action.source = tl_.segment(servo, tl_.count(servo) - 1).at;
        }
      }
    }
    result_.actions.push_back(std::move(action));
  }

  // Records the action's error for servo s, moving to `to`: sampled on curves, at the ends on
  // straight lines (a line against a line is farthest at an end).
  void account(std::size_t s, std::int64_t a, std::int64_t b, int to, bool is_curved) {
    const auto from = intended(s, static_cast<double>(a));
    if (!from) return;
    std::int64_t at = a;
    double err = 0, tol = 0;
    if (is_curved) {
      const double p0 = pos_[s] ? *pos_[s] : std::round(*from);
      const double over = excess(s, a, b, p0, to, &at, &err, &tol);
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
  std::vector<std::optional<int>> pos_;  // each servo's last target
  std::vector<double> inverse_;          // inverse_spans()
  bool free_ = true;                     // whether fit_range() tries free end points
  bool restarted_ = false;               // whether a search stopped short or was cut
  FitResult result_;
};

}  // namespace

FitResult fit_timeline(const Timeline& timeline, const FitOptions& options) {
  return Fitter(timeline, options).run();
}

}  // namespace seqc::compiler
