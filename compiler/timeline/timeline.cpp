#include "compiler/timeline/timeline.hpp"

#include <algorithm>

namespace seqc::compiler {

double Segment::value(double t_ms) const {
  const double t0 = start.value();
  const double t1 = end.value();
  if (kind == CurveKind::Hold || t1 <= t0) return kind == CurveKind::Hold ? from : to;
  const double u = std::clamp((t_ms - t0) / (t1 - t0), 0.0, 1.0);
  switch (kind) {
    case CurveKind::Linear:
      return from + (to - from) * u;
    case CurveKind::Eased:
      return from + (to - from) * easing.at(u);
    case CurveKind::Hermite: {
      // Cubic Hermite basis on [0, 1]; slopes are per ms, so scale them by the length. Written
      // as `from` plus what changes, so a piece with equal ends and no slope is exactly flat.
      const double h = t1 - t0;
      const double u2 = u * u;
      const double u3 = u2 * u;
      return from + (3 * u2 - 2 * u3) * (to - from) + (u3 - 2 * u2 + u) * h * slope_from +
             (u3 - u2) * h * slope_to;
    }
    case CurveKind::Hold:
      break;
  }
  return from;
}

double Segment::velocity(double t_ms) const {
  const double t0 = start.value();
  const double t1 = end.value();
  if (kind == CurveKind::Hold || t1 <= t0) return 0;
  const double h = t1 - t0;
  const double u = std::clamp((t_ms - t0) / h, 0.0, 1.0);
  switch (kind) {
    case CurveKind::Linear:
      return (to - from) / h;
    case CurveKind::Eased:
      return to == from ? 0 : (to - from) * easing.slope(u) / h;
    case CurveKind::Hermite: {
      // d/du of the basis above, divided by the length.
      const double u2 = u * u;
      return ((6 * u2 - 6 * u) * (from - to) + (3 * u2 - 4 * u + 1) * h * slope_from +
              (3 * u2 - 2 * u) * h * slope_to) /
             h;
    }
    case CurveKind::Hold:
      break;
  }
  return 0;
}

ValueRange value_range(const Segment& segment) {
  ValueRange r{std::min(segment.from, segment.to), std::max(segment.from, segment.to)};
  if (segment.is_straight()) return r;
  const double t0 = segment.start.value(), t1 = segment.end.value();
  if (t1 <= t0) return r;
  // 256 samples find the hump or the ring an extreme belongs to (an elastic ease rings about
  // ten times); golden-section search on the intervals beside the best sample then finds the
  // extreme itself, every probe counting (a bounce's extreme is a corner).
  constexpr int kSamples = 256;
  const double h = (t1 - t0) / kSamples;
  int lowest = 0, highest = 0;
  double low = segment.value(t0), high = low;
  for (int i = 1; i <= kSamples; ++i) {
    const double v = segment.value(t0 + h * i);
    if (v < low) low = v, lowest = i;
    if (v > high) high = v, highest = i;
  }
  r.low = std::min(r.low, low);
  r.high = std::max(r.high, high);
  constexpr double g = 0.6180339887498949;
  for (const int sign : {-1, 1}) {  // -1: the lowest point, as the highest of -value
    const int best = sign < 0 ? lowest : highest;
    for (const int side : {-1, 1}) {
      double a = t0 + h * best, b = a + h * side;
      if (b < t0 || b > t1) continue;
      if (a > b) std::swap(a, b);
      for (int k = 0; k < 60; ++k) {
        const double m1 = b - g * (b - a), m2 = a + g * (b - a);
        const double f1 = sign * segment.value(m1), f2 = sign * segment.value(m2);
        if (sign < 0) {
          r.low = std::min({r.low, -f1, -f2});
        } else {
          r.high = std::max({r.high, f1, f2});
        }
        if (f1 < f2) {
          a = m1;
        } else {
          b = m2;
        }
      }
    }
  }
  return r;
}

bool Timeline::Span::same(const Segment& s) const {
  return start == s.start && end == s.end && kind == s.kind && easing == s.easing &&
         tolerance == static_cast<float>(s.tolerance) && keep_boundaries == s.keep_boundaries &&
         at.file == s.at.file && at.line == s.at.line && at.column == s.at.column;
}

void Timeline::add(std::size_t servo, const Segment& s) {
  const std::uint32_t index = span_for(s);
  servos_[servo].push_back({index, static_cast<float>(s.from), static_cast<float>(s.to),
                            static_cast<float>(s.slope_from), static_cast<float>(s.slope_to),
                            s.from_unknown});
}

void Timeline::replace(std::size_t servo, std::size_t first, std::size_t count,
                       const std::vector<Segment>& with) {
  std::vector<Piece> pieces;
  for (const Segment& s : with) {
    pieces.push_back({span_for(s), static_cast<float>(s.from), static_cast<float>(s.to),
                      static_cast<float>(s.slope_from), static_cast<float>(s.slope_to),
                      s.from_unknown});
  }
  std::vector<Piece>& v = servos_[servo];
  const auto at = v.begin() + static_cast<std::ptrdiff_t>(first);
  v.insert(v.erase(at, at + static_cast<std::ptrdiff_t>(count)), pieces.begin(), pieces.end());
}

std::uint32_t Timeline::span_for(const Segment& s) {
  // The servos of a step are added one after another (with `steps`, piece after piece), so
  // the span they share is among the last few.
  std::uint32_t index = static_cast<std::uint32_t>(spans_.size());
  const std::size_t look = std::min<std::size_t>(spans_.size(), 64);
  for (std::size_t k = 1; k <= look; ++k) {
    if (spans_[spans_.size() - k].same(s)) {
      index = static_cast<std::uint32_t>(spans_.size() - k);
      break;
    }
  }
  if (index == spans_.size()) {
    spans_.push_back({s.start, s.end, s.easing, static_cast<float>(s.tolerance), s.kind,
                      s.keep_boundaries, s.at});
  }
  return index;
}

Timeline Timeline::stretched(std::int64_t num, std::int64_t den) const {
  Timeline out = *this;
  const double n = static_cast<double>(num);
  const double d = static_cast<double>(den);
  const auto scale = [&](Instant t) {
    Instant r;
    r.ms = t.ms * n / d;
    return r;
  };
  for (Span& span : out.spans_) {
    span.start = scale(span.start);
    span.end = scale(span.end);
  }
  for (std::vector<Piece>& pieces : out.servos_) {
    for (Piece& p : pieces) {
      p.slope_from = static_cast<float>(static_cast<double>(p.slope_from) * d / n);
      p.slope_to = static_cast<float>(static_cast<double>(p.slope_to) * d / n);
    }
  }
  for (TimelineMarker& m : out.markers) m.at = m.at * ExactMs::ratio(num, den);
  for (TimelineWarning& w : out.warnings) w.at_ms = w.at_ms * n / d;
  out.end = end * ExactMs::ratio(num, den);
  if (written) out.written = std::make_shared<const Timeline>(written->stretched(num, den));
  return out;
}

Segment Timeline::segment(std::size_t servo, std::size_t i) const {
  const Piece& p = servos_[servo][i];
  const Span& span = spans_[p.span];
  Segment s;
  s.start = span.start;
  s.end = span.end;
  s.from = p.from;
  s.to = p.to;
  s.kind = span.kind;
  s.easing = span.easing;
  s.slope_from = p.slope_from;
  s.slope_to = p.slope_to;
  s.tolerance = span.tolerance;
  s.keep_boundaries = span.keep_boundaries;
  s.from_unknown = p.from_unknown;
  s.at = span.at;
  return s;
}

std::optional<std::size_t> Timeline::index_at(std::size_t servo, double t_ms) const {
  if (servo >= servos_.size()) return std::nullopt;
  const std::vector<Piece>& pieces = servos_[servo];
  auto it = std::upper_bound(pieces.begin(), pieces.end(), t_ms, [&](double t, const Piece& p) {
    return t < spans_[p.span].start.value();
  });
  if (it == pieces.begin()) return std::nullopt;
  return static_cast<std::size_t>(it - pieces.begin()) - 1;
}

std::optional<double> Timeline::value(std::size_t servo, double t_ms) const {
  const auto i = index_at(servo, t_ms);
  if (!i) return std::nullopt;
  return segment(servo, *i).value(t_ms);
}

}  // namespace seqc::compiler
