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
      // Cubic Hermite basis on [0, 1]; slopes are per ms, so scale them by the length.
      const double h = t1 - t0;
      const double u2 = u * u;
      const double u3 = u2 * u;
      return (2 * u3 - 3 * u2 + 1) * from + (u3 - 2 * u2 + u) * h * slope_from +
             (-2 * u3 + 3 * u2) * to + (u3 - u2) * h * slope_to;
    }
    case CurveKind::Hold:
      break;
  }
  return from;
}

std::optional<double> Timeline::value(std::size_t servo, double t_ms) const {
  if (servo >= servos.size()) return std::nullopt;
  const std::vector<Segment>& segs = servos[servo];
  // The last segment that starts at or before t.
  auto it = std::upper_bound(segs.begin(), segs.end(), t_ms,
                             [](double t, const Segment& s) { return t < s.start.value(); });
  if (it == segs.begin()) return std::nullopt;
  --it;
  return it->value(t_ms);
}

}  // namespace seqc::compiler
