#include "compiler/targets/servo_controller/tip_depth.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

#include "compiler/program/arm_kinematics.hpp"

namespace seqc::compiler {
namespace {

// A curve's peak speed is taken from its derivative at this many evenly spaced instants, times
// kSpeedHeadroom for a peak between them (the curves are smooth; a sampled move is long).
constexpr int kSpeedSamples = 256;
constexpr double kSpeedHeadroom = 1.25;

// One joint's segments over a move: where it is at any instant of it (nullopt while unknown).
class JointTrack {
 public:
  JointTrack(const Timeline& timeline, std::size_t servo, double start, double end) {
    // From the segment in force at the start (if any) to the last one starting by the end.
    const std::size_t n = timeline.count(servo);
    for (std::size_t i = timeline.index_at(servo, start).value_or(0);
         i < n && timeline.start_of(servo, i).value() <= end; ++i) {
      segments_.push_back(timeline.segment(servo, i));
    }
  }
  // Instants are asked in ascending order.
  std::optional<double> at(double t) {
    while (next_ < segments_.size() && segments_[next_].start.value() <= t) ++next_;
    if (next_ == 0) return std::nullopt;
    return segments_[next_ - 1].value(t);
  }
  // The largest speed (units/ms) and the range of positions over [start, end].
  double peak_speed(double start, double end) const {
    double peak = 0;
    for (const Segment& s : segments_) {
      const double t0 = s.start.value(), t1 = s.end.value();
      if (t1 <= start || t0 >= end || t1 <= t0 || s.kind == CurveKind::Hold) continue;
      if (s.kind == CurveKind::Linear) {
        peak = std::max(peak, std::abs(s.to - s.from) / (t1 - t0));
        continue;
      }
      double curve = 0;
      for (int k = 0; k <= kSpeedSamples; ++k) {
        curve = std::max(curve, std::abs(s.velocity(t0 + (t1 - t0) * k / kSpeedSamples)));
      }
      peak = std::max(peak, curve * kSpeedHeadroom);
    }
    return peak;
  }
  double range(double start, double end) const {
    double low = INFINITY, high = -INFINITY;
    for (const Segment& s : segments_) {
      if (s.end.value() < start || s.start.value() > end) continue;
      const ValueRange r = value_range(s);
      low = std::min(low, r.low);
      high = std::max(high, r.high);
    }
    return high >= low ? high - low : 0;
  }

 private:
  std::vector<Segment> segments_;
  std::size_t next_ = 0;
};

struct MoveDip {
  double depth = 0, at_ms = 0, below_ms = 0;
  std::array<double, 4> joints{};
};

std::optional<MoveDip> move_dip(const ArmGeometry& arm, const std::array<std::size_t, 4>& joints,
                                const Timeline& timeline, const ArmMove& move) {
  const double a = move.start.value(), b = move.end.value();
  if (b < a) return std::nullopt;
  std::vector<JointTrack> tracks;
  for (const std::size_t servo : joints) tracks.emplace_back(timeline, servo, a, b);
  const bool sampled = b - a > kEveryMsUpTo;
  // Instants a + k * spacing for k below `count`, then the end itself.
  const std::uint64_t count =
      sampled ? kLongSamples : static_cast<std::uint64_t>(std::ceil(b - a - 1e-9));
  const double spacing = sampled ? (b - a) / kLongSamples : 1.0;
  double margin = 0;
  if (sampled) {
    // The tip's height changes with the shoulder, elbow and wrist only, each by its angle's
    // change times the links beyond it.
    const double beyond[] = {arm.upper_arm + arm.forearm + arm.hand, arm.forearm + arm.hand,
                             arm.hand};
    const double radians_per_unit = arm.degrees_per_unit * std::numbers::pi / 180;
    for (std::size_t j = 1; j < 4; ++j) {
      const double by_speed = spacing / 2 * tracks[j].peak_speed(a, b) * radians_per_unit;
      const double by_range = tracks[j].range(a, b) * radians_per_unit;
      margin += beyond[j - 1] * std::min(by_speed, by_range);
    }
  }
  std::optional<double> z_start;
  std::optional<double> z_end;
  struct Sample {
    double t, z;
    std::array<double, 4> joints;
  };
  std::optional<Sample> deepest;
  std::uint64_t below = 0;
  std::vector<Sample> samples;
  samples.reserve(count + 1);
  for (std::uint64_t k = 0; k <= count; ++k) {
    const double t = k == count ? b : a + static_cast<double>(k) * spacing;
    std::array<double, 4> q{};
    bool known = true;
    for (std::size_t j = 0; j < 4 && known; ++j) {
      const std::optional<double> v = tracks[j].at(t);
      known = v.has_value();
      if (known) q[j] = *v;
    }
    if (!known) continue;
    const double z = tip_height(arm, q);
    if (k == 0) z_start = z;
    if (k == count) z_end = z;
    samples.push_back({t, z, q});
  }
  // What the move's ends excuse (tip_depth.hpp).
  double excused = move.line_tolerance_mm;
  if (z_start) excused = std::max(excused, -*z_start);
  if (move.tip_end && z_end) excused = std::max(excused, -*z_end);
  for (const Sample& s : samples) {
    const double low = s.z - margin;
    if (low >= -excused - 1e-9) continue;
    ++below;
    if (!deepest || low < deepest->z) deepest = Sample{s.t, low, s.joints};
  }
  if (!deepest) return std::nullopt;
  return MoveDip{-deepest->z, deepest->t, static_cast<double>(below) * spacing, deepest->joints};
}

}  // namespace

std::vector<TipDip> find_tip_dips(const compiler::ArmGeometry& arm,
                                  const std::array<std::size_t, 4>& joints,
                                  const Timeline& timeline, const std::vector<ArmMove>& moves) {
  std::vector<TipDip> out;
  for (const ArmMove& move : moves) {
    const std::optional<MoveDip> dip = move_dip(arm, joints, timeline, move);
    if (!dip) continue;
    auto same =
        std::find_if(out.begin(), out.end(), [&](const TipDip& d) { return d.at == move.at; });
    if (same != out.end() && same->depth_mm >= dip->depth) continue;
    TipDip d{move.at, dip->depth, dip->at_ms, arm_points(arm, dip->joints).tip, dip->below_ms};
    if (same != out.end()) {
      *same = d;
    } else {
      out.push_back(d);
    }
  }
  return out;
}

}  // namespace seqc::compiler
