#include "compiler/fitting/fitter.hpp"

#include "compiler/fitting/free_search.hpp"
#include "compiler/fitting/on_curve_search.hpp"
#include "compiler/fitting/search_memo.hpp"
#include "compiler/fitting/stretch.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <iterator>
#include <optional>
#include <tuple>
#include <utility>

namespace seqc::compiler {

namespace {

using fitting::free_joint_search;
using fitting::free_single_search;
using fitting::joint_cap;
using fitting::joint_grid;
using fitting::kMaxValues;
using fitting::kNoKey;
using fitting::on_curve_search;
using fitting::Path;
using fitting::SearchKey;
using fitting::SearchKind;
using fitting::SearchLimits;
using fitting::Stretch;
using fitting::StretchSource;

// Instants at which an action of a long stretch is checked (fine stretches: every millisecond).
constexpr std::int64_t kCoarseCheckPoints = 64;
// A stretch whose actions may run across knots is searched beside the fit that keeps them, and
// kept only where it saves actions, so its joint free search may spend more (kAcrossWork x its
// cap) on a finer grid of boundaries (kAcrossGrid x finer): the coarse grid that keeps an
// ordinary stretch's search cheap would give up most of what crossing the knots can save.
constexpr std::size_t kAcrossWork = 3;
constexpr std::size_t kAcrossGrid = 2;
// After a shortfall in a long stretch, how far (in samples, at least four longest actions) the
// next search looks before a cut: each search after a shortfall starts again from it, so
// without a window the searches of a stretch that misses often would cost shortfalls x length.
constexpr std::size_t kCoarseWindow = 1000;

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
    pos_.resize(tracks_.size());
    for (const TimelineMarker& m : tl_.markers) marks_.push_back(m.at.round());
    std::sort(marks_.begin(), marks_.end());
  }

  FitResult run() {
    knots_ = collect_knots();
    std::vector<char> exact(knots_.size(), 1);
    for (std::size_t i = 1; i + 1 < knots_.size(); ++i) exact[i] = exact_knot(knots_[i]) ? 1 : 0;
    std::size_t j = 0, plain = 0;  // [plain, j): intervals no action may run across
    while (j + 1 < knots_.size()) {
      // Actions may run across a knot inside a move: a point of the curve like any other, the
      // servos whose knot it is being curved servos of the stretch.
      std::vector<std::size_t> curved = curved_in(knots_[j], knots_[j + 1]);
      std::size_t end = j + 1;
      while (end + 1 < knots_.size() && exact[end] == 0) {
        auto joined = crossing(curved, knots_[j], knots_[end], knots_[end + 1]);
        if (!joined) break;
        curved = std::move(*joined);
        ++end;
      }
      if (end == j + 1) {
        ++j;
        continue;
      }
      fit_knots_kept(plain, j);
      fit_across(curved, j, end);
      plain = j = end;
    }
    fit_knots_kept(plain, knots_.size() - 1);
    return std::move(result_);
  }

 private:
  void fit_sampled(const std::vector<std::size_t>& curved, std::int64_t a,
                   const std::vector<std::int64_t>& inner) {
    const Stretch in = sample(curved, a, inner);
    memo_.enter(in, {curved, a, inner},
                [this](const StretchSource& x) { return sample(x.curved, x.a, x.inner); });
    fit_stretch(in, curved);
  }

  // The whole millisecond of sample t of a stretch.
  static std::int64_t ms_of(const Stretch& in, std::size_t t) {
    if (in.step == 1) return in.a + static_cast<std::int64_t>(t);
    return in.a + std::llround(static_cast<double>(t) * in.step);
  }

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

  // A first move from an unknown position is named only by the action that ends with it.
  static bool waits_for_its_end(const Segment& seg, std::int64_t action_end) {
    return seg.from_unknown && action_end < seg.end.round();
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
    // Every millisecond, but in a long stretch (whose bands kept a margin for the instants
    // between samples) about two per sample it spans and at most kCoarseCheckPoints + 1 evenly
    // spaced ones, so that the check costs the same for any length.
    const std::int64_t len = b - a;
    const auto per_samples =
        static_cast<std::int64_t>(2 * std::ceil(static_cast<double>(len) / coarse_step_)) + 2;
    const std::int64_t count = coarse_ ? std::min({len, kCoarseCheckPoints, per_samples}) : len;
    for (std::int64_t i = 0; i <= count; ++i) {
      const std::int64_t t = count == len ? a + i : a + len * i / count;
      const double td = static_cast<double>(t);
      const double line = controller_output(
          opt_.model, p0 + (p1 - p0) * (td - static_cast<double>(a)) / static_cast<double>(b - a));
      const std::optional<Segment> seg = segment_at(s, td);  // intended(s, td) is its value
      const double want = seg ? seg->value(td) : line;
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

  // Knots q..end with every knot an action boundary: a stretch goes on over a knot while the
  // same servos are curved on both sides and one of them is mid-curve there (its own segments
  // go on): that one's target there is free.
  void fit_knots_kept(std::size_t q, std::size_t end) {
    while (q < end) {
      const std::vector<std::size_t> curved = curved_in(knots_[q], knots_[q + 1]);
      if (curved.empty()) {
        fit_straight(knots_[q], knots_[q + 1]);
        ++q;
        continue;
      }
      std::size_t e = q + 1;
      while (e < end && curved_in(knots_[e], knots_[e + 1]) == curved &&
             !std::all_of(curved.begin(), curved.end(),
                          [&](std::size_t s) { return has_knot(s, knots_[e]); })) {
        ++e;
      }
      if (knots_[e] - knots_[q] <= fitting::kFineMs) {
        const std::vector<std::int64_t> inner(knots_.begin() + static_cast<std::ptrdiff_t>(q) + 1,
                                              knots_.begin() + static_cast<std::ptrdiff_t>(e) + 1);
        fit_sampled(curved, knots_[q], inner);
      } else {
        // A long stretch is fitted knot by knot, each interval sampled on its own grid (a
        // servo mid-curve there has its target pinned, as at a cut).
        for (std::size_t i = q; i < e; ++i) fit_sampled(curved, knots_[i], {knots_[i + 1]});
      }
      q = e;
    }
  }

  // Knots q..end, the ones inside crossable: fitted with every knot a boundary and as one
  // stretch whose actions may run across them, the latter kept only where it saves actions
  // without a shortfall the former avoids (so a fit never costs an action, and knots stay
  // boundaries where crossing them gains nothing).
  void fit_across(const std::vector<std::size_t>& curved, std::size_t q, std::size_t end) {
    const std::size_t actions = result_.actions.size(), shortfalls = result_.shortfalls.size();
    const auto error =
        std::make_tuple(result_.max_error, result_.max_error_at_ms, result_.max_error_servo);
    const std::vector<std::optional<int>> pos = pos_;
    fit_knots_kept(q, end);
    std::vector<FittedAction> kept(
        std::make_move_iterator(result_.actions.begin() + static_cast<std::ptrdiff_t>(actions)),
        std::make_move_iterator(result_.actions.end()));
    std::vector<FitShortfall> kept_short(
        result_.shortfalls.begin() + static_cast<std::ptrdiff_t>(shortfalls),
        result_.shortfalls.end());
    const auto kept_error =
        std::make_tuple(result_.max_error, result_.max_error_at_ms, result_.max_error_servo);
    std::vector<std::optional<int>> kept_pos = std::move(pos_);
    result_.actions.resize(actions);
    result_.shortfalls.resize(shortfalls);
    std::tie(result_.max_error, result_.max_error_at_ms, result_.max_error_servo) = error;
    pos_ = pos;
    across_ = true;
    fit_sampled(curved, knots_[q], {knots_[end]});
    across_ = false;
    if (result_.actions.size() - actions < kept.size() &&
        result_.shortfalls.size() - shortfalls <= kept_short.size()) {
      return;
    }
    result_.actions.resize(actions);
    result_.actions.insert(result_.actions.end(), std::make_move_iterator(kept.begin()),
                           std::make_move_iterator(kept.end()));
    result_.shortfalls.resize(shortfalls);
    result_.shortfalls.insert(result_.shortfalls.end(), kept_short.begin(), kept_short.end());
    std::tie(result_.max_error, result_.max_error_at_ms, result_.max_error_servo) = kept_error;
    pos_ = std::move(kept_pos);
  }

  // Whether knot k (with the boundaries merged into it) stays an exact action boundary: a
  // marked moment (an `at:` cue, a section, a tempo or meter change), or where some servo starts
  // or stops moving, holds, begins its first move, or has `steps:` or `path: line` pieces (whose
  // boundaries are the actions). Elsewhere every servo whose knot it is goes on moving through
  // it, and the knot is a point of the curve like any other.
  bool exact_knot(std::int64_t k) const {
    const std::int64_t min = opt_.min_action_ms;
    const auto near = std::lower_bound(marks_.begin(), marks_.end(), k - min + 1);
    if (near != marks_.end() && *near < k + min) return true;
    for (std::size_t s = 0; s < tracks_.size(); ++s) {
      const RoundedTrack& t = tracks_[s];
      // Segment i's start is the join (i - 1, i); segment i's end is the join (i, i + 1).
      for (std::size_t side = 0; side < 2; ++side) {
        const std::vector<std::int64_t>& v = side == 0 ? t.start : t.end;
        for (auto it = std::lower_bound(v.begin(), v.end(), k - min + 1);
             it != v.end() && *it < k + min; ++it) {
          const auto i = static_cast<std::size_t>(it - v.begin()) + side;
          if (!smooth_join(s, i)) return true;
        }
      }
    }
    return false;
  }

  // Whether servo s's segment i begins where segment i - 1 ends, both moving, neither a first
  // move from an unknown position nor a piece whose boundaries are kept.
  bool smooth_join(std::size_t s, std::size_t i) const {
    if (i == 0 || i >= tl_.count(s) || tracks_[s].end[i - 1] != tracks_[s].start[i]) return false;
    const Segment x = tl_.segment(s, i - 1), y = tl_.segment(s, i);
    auto moving = [](const Segment& g) {
      if (g.kind == CurveKind::Hold || g.keep_boundaries || g.from_unknown) return false;
      return g.from != g.to ||
             (g.kind == CurveKind::Hermite && (g.slope_from != 0 || g.slope_to != 0));
    };
    return moving(x) && moving(y);
  }

  // Whether an action worth having could run across knot k: one of twice the shortest length
  // reaching at least half the shortest either side of k, as the servos in `servos` must all
  // follow it. A line within tolerance over it differs from the chord between the curve's
  // values at its ends by at most the tolerance, so the chord must stay within twice the
  // tolerance of the curve. Where none does (a turn, a sharp bend), k stays a boundary: an
  // action across it could only graze it, and searching for one would cost time, not actions.
  bool may_cross(const std::vector<std::size_t>& servos, std::int64_t k) const {
    const std::int64_t min = opt_.min_action_ms, len = 2 * min;
    for (std::int64_t a = k - len + min / 2; a <= k - min / 2; ++a) {
      const std::int64_t b = a + len;
      bool fits = true;
      for (std::size_t s : servos) {
        const auto v0 = intended(s, static_cast<double>(a));
        const auto v1 = intended(s, static_cast<double>(b));
        if (!v0 || !v1) return false;
        for (std::int64_t t = a + 1; t < b && fits; ++t) {
          const std::optional<Segment> seg = segment_at(s, static_cast<double>(t));
          const double chord =
              *v0 + (*v1 - *v0) * static_cast<double>(t - a) / static_cast<double>(len);
          const double want = intended(s, static_cast<double>(t)).value_or(chord);
          fits = std::abs(chord - want) <= 2 * (seg ? seg->tolerance : 1.0) + 1e-9;
        }
        if (!fits) break;
      }
      if (fits) return true;
    }
    return false;
  }

  // The curved servos of a stretch from a that goes on over knot k (not exact) to b: those of
  // [a, k], of [k, b] and those whose knot k is, provided each has one unbroken run of segments
  // over all of [a, b] (nullopt otherwise, or past kFineMs: then k is a boundary).
  std::optional<std::vector<std::size_t>> crossing(const std::vector<std::size_t>& curved,
                                                   std::int64_t a, std::int64_t k,
                                                   std::int64_t b) const {
    if (b - a > fitting::kFineMs) return std::nullopt;
    std::vector<std::size_t> joined = curved_in(k, b);
    joined.insert(joined.end(), curved.begin(), curved.end());
    for (std::size_t s = 0; s < tracks_.size(); ++s) {
      if (has_knot(s, k)) joined.push_back(s);
    }
    std::sort(joined.begin(), joined.end());
    joined.erase(std::unique(joined.begin(), joined.end()), joined.end());
    for (std::size_t s : joined) {
      const auto [first, last] = overlapping(s, a, b);
      const RoundedTrack& t = tracks_[s];
      if (first == last || t.start[first] > a || t.end[last - 1] < b) return std::nullopt;
      for (std::size_t i = first; i < last; ++i) {
        if (tl_.segment(s, i).from_unknown) return std::nullopt;
        if (i > first && t.start[i] != t.end[i - 1]) return std::nullopt;
      }
    }
    if (!may_cross(joined, k)) return std::nullopt;
    return joined;
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

  // The stretch from knot a over the knots `inner` (its end last): every millisecond up to
  // kFineMs; a longer one (then `inner` is its end alone) at evenly spaced instants, each band
  // narrowed by a margin that keeps the controller within tolerance between them and when the
  // boundaries are rounded to whole milliseconds (coarse_margins()). Under a rounding model the
  // band is where the line may be so that the rounded output is within tolerance whatever the
  // instant: tol less the rounding's reach.
  Stretch sample(const std::vector<std::size_t>& curved, std::int64_t a,
                 const std::vector<std::int64_t>& inner) const {
    const std::int64_t b = inner.back();
    Stretch in;
    in.a = a;
    const bool coarse = b - a > fitting::kFineMs;
    const double samples = std::min<double>(
        fitting::kCoarseSamples,
        std::sqrt(fitting::kCoarseWork * static_cast<double>(b - a) / opt_.max_action_ms));
    const std::size_t n = in.n =
        coarse ? std::max<std::size_t>(static_cast<std::size_t>(samples),
                                       static_cast<std::size_t>(4 * (b - a) / opt_.max_action_ms))
               : static_cast<std::size_t>(b - a);
    in.step = coarse ? static_cast<double>(b - a) / static_cast<double>(n) : 1.0;
    const std::size_t k = in.k = curved.size();
    for (auto* v : {&in.want, &in.lo, &in.hi, &in.tol}) v->resize(k * (n + 1));
    for (auto* v : {&in.pin, &in.vlo, &in.vhi}) v->resize(k * (n + 1));
    in.pinned.resize(k * (n + 1));
    in.next_knot.resize(n + 1);
    in.is_knot.resize(n + 1);
    std::size_t next = n;
    for (std::size_t t = n + 1; t-- > 0;) {
      in.next_knot[t] = static_cast<std::uint32_t>(next);
      if (coarse
              ? t == n
              : std::binary_search(inner.begin(), inner.end(), a + static_cast<std::int64_t>(t))) {
        next = t;
        in.is_knot[t] = 1;
      }
    }
    for (std::int64_t knot : inner) {
      const std::size_t t = coarse ? n : static_cast<std::size_t>(knot - a);
      for (std::size_t i = 0; i < k; ++i)
        in.pinned[in.at(i, t)] = has_knot(curved[i], knot) ? 1 : 0;
    }
    for (std::size_t i = 0; i < k; ++i) {
      const ServoLimits lim = limits(curved[i]);
      for (std::size_t t = 0; t <= n; ++t) {
        double at = static_cast<double>(a + static_cast<std::int64_t>(t));
        if (coarse) {  // the last sample at the stretch's end exactly
          at = t == n ? static_cast<double>(b)
                      : static_cast<double>(a) + static_cast<double>(t) * in.step;
        }
        const std::size_t x = in.at(i, t);
        in.want[x] = intended(curved[i], at).value_or(0);
        const std::optional<Segment> seg = segment_at(curved[i], at);
        const double tol = (seg ? seg->tolerance : 1.0) + 1e-9;
        in.tol[x] = tol;
      }
      const std::vector<double> margins = coarse ? coarse_margins(in, i) : std::vector<double>();
      for (std::size_t t = 0; t <= n; ++t) {
        const std::size_t x = in.at(i, t);
        const double w = in.want[x];
        // What the search may use of the tolerance: all of it, or in a long stretch what the
        // margin leaves.
        const double tol = coarse ? std::max(0.0, in.tol[x] - margins[t]) : in.tol[x];
        std::tie(in.lo[x], in.hi[x]) = coarse ? coarse_band(w, tol) : line_band(w, tol);
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

  // The margin at each sample of servo i of a long stretch (its `want` and `tol` filled in): how
  // far the controller may stray from what the search sees there. Between two samples a line's
  // distance from the curve bends by at most max|w''| step^2 / 8 (the second differences around
  // the sample, taken twice over); and a boundary rounded to its whole millisecond moves by at
  // most 0.5 ms, which moves a line by half its slope, at most the curve's steepest over the
  // longest action around the sample plus 2 tol over the shortest action.
  std::vector<double> coarse_margins(const Stretch& in, std::size_t i) const {
    const std::size_t n = in.n;
    auto w = [&](std::size_t t) { return in.want[in.at(i, t)]; };
    std::vector<double> slope(n + 1, 0), bend(n + 1, 0);
    for (std::size_t t = 0; t < n; ++t) slope[t] = std::abs(w(t + 1) - w(t)) / in.step;
    if (n > 0) slope[n] = slope[n - 1];
    for (std::size_t t = 1; t < n; ++t) bend[t] = std::abs(w(t + 1) - 2 * w(t) + w(t - 1));
    // The steepest slope within the longest action either side (a sliding maximum).
    const auto reach = static_cast<std::size_t>(std::ceil(opt_.max_action_ms / in.step)) + 1;
    std::vector<double> steepest(n + 1, 0);
    std::deque<std::size_t> window;  // indices of decreasing slopes
    for (std::size_t t = 0, next = 0; t <= n; ++t) {
      for (; next <= std::min(n, t + reach); ++next) {
        while (!window.empty() && slope[window.back()] <= slope[next]) window.pop_back();
        window.push_back(next);
      }
      while (window.front() + reach < t) window.pop_front();
      steepest[t] = slope[window.front()];
    }
    std::vector<double> out(n + 1);
    const double shortest = static_cast<double>(opt_.min_action_ms);
    for (std::size_t t = 0; t <= n; ++t) {
      double b = bend[t];
      if (t > 0) b = std::max(b, bend[t - 1]);
      if (t < n) b = std::max(b, bend[t + 1]);
      out[t] = b / 4 + 0.5 * (steepest[t] + 2 * in.tol[in.at(i, t)] / shortest) + 1e-9;
    }
    return out;
  }

  // Where the straight line may pass at a sample of a long stretch where the curve is at `want`
  // and the tolerance less the margin is `tol`, so that what the controller puts out is within
  // tolerance at any instant near it: the rounding's reach taken off (empty bands shrink to the
  // curve, whose actions then miss and say so).
  std::pair<double, double> coarse_band(double want, double tol) const {
    double lo = want - tol, hi = want + tol;
    switch (opt_.model) {
      case ControllerModel::StraightLine:
        break;
      case ControllerModel::Rounds:  // |round(x) - x| <= 0.5
        lo += 0.5;
        hi -= 0.5;
        break;
      case ControllerModel::Truncates:  // x - 1 < trunc(x) <= x, positions being non-negative
        lo += 1;
        break;
    }
    if (lo > hi) lo = hi = want;
    return {lo, hi};
  }

  // Fits a stretch. Each search keeps the free fit only when it beats the on-curve one, but where
  // a search stops short (a shortfall) or is cut, the searches after it start from different
  // places; then the whole stretch is fitted on the curve as well, and the fit with fewer
  // shortfalls (then fewer actions) kept.
  void fit_stretch(const Stretch& in, const std::vector<std::size_t>& curved) {
    // As long as the longest action this stretch can hold (a program of straight moves needs
    // none: the table is not allocated for it).
    coarse_ = in.step != 1;
    coarse_step_ = in.step;
    if (in.step == 1) {
      min_samples_ = opt_.min_action_ms;
      max_samples_ = opt_.max_action_ms;
    } else {
      // Lengths in samples whose actions, their ends rounded to whole ms, stay within the limits.
      const double shortest = opt_.min_action_ms + 1.0;
      min_samples_ = static_cast<std::size_t>(std::ceil(shortest / in.step));
      max_samples_ = static_cast<std::size_t>(std::floor((opt_.max_action_ms - 1.0) / in.step));
      max_samples_ = std::max(max_samples_, min_samples_);
    }
    const std::size_t spans = std::min<std::size_t>(in.n, max_samples_) + 1;
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
    // Only this stretch's part of the result is set aside between the two fits: copying all of
    // it per stretch would make a dance's cost the square of its actions.
    const std::size_t actions_before = result_.actions.size();
    const std::size_t shortfalls_before = result_.shortfalls.size();
    const FitResult worst_before = worst_only(result_);
    const std::vector<std::optional<int>> pos_before = pos_;
    restarted_ = false;
    free_ = true;
    fit_range(in, curved, 0, in.n);
    if (!restarted_) return;
    FitResult with_free = worst_only(result_);
    with_free.actions.assign(std::make_move_iterator(result_.actions.begin() +
                                                     static_cast<std::ptrdiff_t>(actions_before)),
                             std::make_move_iterator(result_.actions.end()));
    with_free.shortfalls.assign(
        result_.shortfalls.begin() + static_cast<std::ptrdiff_t>(shortfalls_before),
        result_.shortfalls.end());
    result_.actions.resize(actions_before);
    result_.shortfalls.resize(shortfalls_before);
    set_worst(result_, worst_before);
    std::vector<std::optional<int>> pos_free = std::move(pos_);
    pos_ = pos_before;
    free_ = false;
    fit_range(in, curved, 0, in.n);
    free_ = true;
    // Where one fit is no worse in both actions and worst miss (over this stretch), it is kept
    // (fewer shortfalls deciding a tie). Otherwise one saves actions and the other misses by
    // less: fewer shortfalls decide, then fewer actions. So an action more than the on-curve fit
    // is only ever spent on a smaller worst miss, never on more misses of the same size, and a
    // miss the on-curve fit avoids is never made.
    auto worst_miss = [](auto from, auto to) {
      double most = 0;
      for (auto it = from; it != to; ++it) most = std::max(most, it->error);
      return most;
    };
    const double free_worst = worst_miss(with_free.shortfalls.begin(), with_free.shortfalls.end());
    const double on_worst =
        worst_miss(result_.shortfalls.begin() + static_cast<std::ptrdiff_t>(shortfalls_before),
                   result_.shortfalls.end());
    const std::size_t free_actions = with_free.actions.size();
    const std::size_t on_actions = result_.actions.size() - actions_before;
    const auto free_count = std::make_pair(with_free.shortfalls.size(), free_actions);
    const auto on_count = std::make_pair(result_.shortfalls.size() - shortfalls_before, on_actions);
    bool keep_free = free_count < on_count;  // a trade of actions against the worst miss
    if (free_worst <= on_worst + 1e-6 && free_actions <= on_actions) {
      keep_free = free_actions < on_actions || free_count < on_count;  // no worse in both
    } else if (free_worst >= on_worst - 1e-6 && free_actions >= on_actions) {
      keep_free = false;  // the on-curve fit is no worse in both
    }
    if (keep_free) {
      result_.actions.resize(actions_before);
      result_.shortfalls.resize(shortfalls_before);
      std::move(with_free.actions.begin(), with_free.actions.end(),
                std::back_inserter(result_.actions));
      result_.shortfalls.insert(result_.shortfalls.end(), with_free.shortfalls.begin(),
                                with_free.shortfalls.end());
      set_worst(result_, with_free);
      pos_ = std::move(pos_free);
    }
  }

  // A result's worst error and where it is, without its actions and shortfalls.
  static FitResult worst_only(const FitResult& r) {
    FitResult w;
    set_worst(w, r);
    return w;
  }
  static void set_worst(FitResult& to, const FitResult& from) {
    to.max_error = from.max_error;
    to.max_error_at_ms = from.max_error_at_ms;
    to.max_error_servo = from.max_error_servo;
  }

  // Fits [first, last] of the stretch (ms from its start; both ends pinned on the rounded
  // curve): the better of the two searches, shortfalls where neither reaches the end, and a cut
  // in two where a search runs over its budget.
  void fit_range(const Stretch& in, const std::vector<std::size_t>& curved, std::size_t first,
                 std::size_t last) {
    const std::size_t min = min_samples_;
    std::size_t cur = first;
    while (cur < last) {
      std::size_t work_on = 0, work_free = 0;
      Path best;
      const int greedy = free_ && in.k == 1
                             ? fitting::greedy_on_curve_key(in, search_limits(), cur, last)
                             : kNoKey;
      const bool exact_alone = greedy != kNoKey && free_first(in, cur, last, greedy);
      if (exact_alone) {
        // Every on-curve fit is one of the exact free search's, so it looks first, for fewer
        // actions than a greedy walk along the rounded curve needs (among as few, it prefers
        // targets on the curve). The on-curve search runs only where it finds none (then the
        // greedy walk had the fewest, and the on-curve search finds its own fit with as many)
        // or none reaches the end (then the farther of the two is kept).
        best = search(SearchKind::FreeSingle, in, cur, last, greedy, 0, 0, work_free);
        if (!best.complete && !best.gave_up) {
          Path on = on_curve(in, cur, last, work_on);
          if (!better(best, on)) best = std::move(on);
        }
      } else {
        best = on_curve(in, cur, last, work_on);
      }
      if (free_ && !exact_alone && !best.gave_up) {
        // The free fit looks only for fewer actions than the on-curve one found.
        const int bound = best.complete ? best.key : kNoKey;
        Path free = in.k == 1
                        ? search(SearchKind::FreeSingle, in, cur, last, bound, 0, 0, work_free)
                        : search(SearchKind::FreeJoint, in, cur, last, bound,
                                 grid(in, cur, last, work_on), cap(work_on), work_free);
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
      const std::size_t window = std::max(kCoarseWindow, 4 * max_samples_);
      if (coarse_ && last - cur > 2 * window) {
        const std::size_t cut = cut_point(in, cur, cur + 2 * window);
        if (cut > cur) {
          fit_range(in, curved, cur, cut);
          fit_range(in, curved, cut, last);
          return;
        }
      }
    }
  }

  // Whether the free search of one curved servo over [first, last] goes first, the on-curve
  // search only where it is needed (fit_range()): where the rounded curve is among the free
  // targets at every ms (then every on-curve fit is also a free fit; it is not where the
  // tolerance is below half a unit), and where the free search is expected to stay well within
  // its budget. It tries about (band width) x (length) x (action length) lines, the greedy walk
  // (its key `greedy`) telling the action length; past a quarter of the budget, the on-curve
  // search goes first as it always did, since a search that gives up is time lost.
  bool free_first(const Stretch& in, std::size_t first, std::size_t last, int greedy) const {
    std::size_t width = 1;
    for (std::size_t t = first + 1; t <= last; ++t) {
      const std::size_t x = in.at(0, t);
      if (t == last || in.pinned[x] != 0) continue;
      if (in.pin[x] < in.vlo[x] || in.pin[x] > in.vhi[x]) return false;
      width = std::max<std::size_t>(width, static_cast<std::size_t>(in.vhi[x] - in.vlo[x] + 1));
    }
    const double len = static_cast<double>(last - first);
    const double actions = std::max(1, greedy / 2);
    return static_cast<double>(width) * len * len / actions <= fitting::kWorkBudget / 4.0;
  }

  // The joint free search's grid and cap (free_search.hpp) after the on-curve search spent `on`.
  std::size_t grid(const Stretch& in, std::size_t first, std::size_t last, std::size_t on) const {
    const std::size_t g = joint_grid(in, first, last, on);
    return across_ ? std::max<std::size_t>(1, g / kAcrossGrid) : g;
  }
  std::size_t cap(std::size_t on) const { return joint_cap(on) * (across_ ? kAcrossWork : 1); }

  SearchLimits search_limits() const { return {min_samples_, max_samples_, &inverse_}; }

  // The on-curve search of [first, last] of the current stretch, and the work it spent.
  Path on_curve(const Stretch& in, std::size_t first, std::size_t last, std::size_t& work) {
    return search(SearchKind::OnCurve, in, first, last, kNoKey, 0, 0, work);
  }

  // One search of [first, last] of the current stretch, and the work it spent: run once per
  // stretch content (search_memo.hpp).
  Path search(SearchKind kind, const Stretch& in, std::size_t first, std::size_t last, int bound,
              std::size_t grid, std::size_t cap, std::size_t& work) {
    const SearchKey key{kind, first, last, bound, grid, cap};
    if (const auto* found = memo_.find(key)) {
      work = found->second;
      return found->first;
    }
    std::size_t spent = 0;
    Path path;
    switch (kind) {
      case SearchKind::OnCurve:
        path = on_curve_search(in, search_limits(), first, last, spent);
        break;
      case SearchKind::FreeSingle:
        path = free_single_search(in, search_limits(), first, last, bound, spent);
        break;
      case SearchKind::FreeJoint:
        path = free_joint_search(in, search_limits(), first, last, bound, grid, cap, spent);
        break;
    }
    memo_.store(key, path, spent);
    work = spent;
    return path;
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
    const std::size_t min = min_samples_;
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

  // Emits an action of the stretch from ms s to e (from its start), with the curved servos'
  // targets in `values` (the knot's own rule at the stretch's end).
  void emit_curved(const Stretch& in, const std::vector<std::size_t>& curved, std::size_t s,
                   std::size_t e, const int* values) {
    std::vector<std::optional<int>> free(tracks_.size());
    for (std::size_t i = 0; i < in.k && e < in.n; ++i) {
      if (in.pinned[in.at(i, e)] == 0) free[curved[i]] = values[i];
    }
    emit(ms_of(in, s), ms_of(in, e), &curved, &free);
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
      if (waits_for_its_end(seg, e)) continue;
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
        const std::optional<Segment> seg = segment_at(servo, static_cast<double>(s));
        if (seg && waits_for_its_end(*seg, e)) continue;
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
  std::vector<std::int64_t> knots_;      // collect_knots()
  std::vector<std::int64_t> marks_;      // the markers' instants, rounded, ascending
  std::vector<std::optional<int>> pos_;  // each servo's last target
  std::vector<double> inverse_;          // SearchLimits::inverse
  std::size_t min_samples_ = 20;         // the current stretch's action lengths, in samples
  std::size_t max_samples_ = 30000;
  bool coarse_ = false;       // whether the current stretch is sampled coarser
  double coarse_step_ = 1;    // and its ms per sample
  fitting::SearchMemo memo_;  // the searches run so far, by stretch content
  bool free_ = true;          // whether fit_range() tries free end points
  bool restarted_ = false;    // whether a search stopped short or was cut
  bool across_ = false;       // whether the current stretch runs across knots (fit_across())
  FitResult result_;
};

}  // namespace

FitResult fit_timeline(const Timeline& timeline, const FitOptions& options) {
  return Fitter(timeline, options).run();
}

FitResult fit_timeline_on_board(const Timeline& timeline, const FitOptions& options,
                                std::int32_t clock_ppm) {
  if (clock_ppm == 0) return fit_timeline(timeline, options);
  return fit_timeline(timeline.stretched(1000000 + std::int64_t{clock_ppm}, 1000000), options);
}

}  // namespace seqc::compiler
