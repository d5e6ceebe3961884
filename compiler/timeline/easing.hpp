// Easing curves: the shape of a move from 0 (start) to 1 (end) over normalised time 0..1.
// The language's names (docs/language.md, "Easing"): `linear`; `in`, `out`, `in-out` (the
// quadratic ones); the families quad, cubic, quart, quint, sine, expo, circ, back, elastic and
// bounce, each as -in, -out and -in-out; and `cubic-bezier(x1, y1, x2, y2)` with CSS
// semantics. `back` and `elastic` overshoot (values outside 0..1), so a move's limits are
// checked along the whole curve, not only at its ends.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace seqc::compiler {

enum class EaseFamily {
  Linear,
  Quad,
  Cubic,
  Quart,
  Quint,
  Sine,
  Expo,
  Circ,
  Back,
  Elastic,
  Bounce,
  Bezier
};
enum class EaseMode { In, Out, InOut };

struct Easing {
  EaseFamily family = EaseFamily::Linear;
  EaseMode mode = EaseMode::InOut;
  double x1 = 0, y1 = 0, x2 = 1, y2 = 1;  // cubic-bezier control points

  bool is_linear() const { return family == EaseFamily::Linear; }
  // The eased fraction at normalised time t in [0, 1]; at(0) = 0 and at(1) = 1.
  double at(double t) const;
  // d at / dt at t in [0, 1], one-sided at the ends (never across them). Infinite where the
  // curve is vertical: circ at the end of its -in half, a cubic-bezier with x'(s) = 0.
  double slope(double t) const;
  // The name as written in a file ("sine-in-out", "cubic-bezier(0.42, 0, 0.58, 1)").
  std::string name() const;
  friend bool operator==(const Easing&, const Easing&) = default;
};

// Parses an easing name. On failure, the message says what is wrong (for cubic-bezier: which
// number, or an x outside [0, 1]); an unknown name gives an empty message so the caller can
// report it with "did you mean".
struct EaseParse {
  std::optional<Easing> easing;
  std::string message;
};
EaseParse parse_easing(std::string_view text);

// Every name parse_easing() accepts except cubic-bezier, for "did you mean" and the docs.
const std::vector<std::string>& easing_names();
// The same names in one line for a message: "easings: linear, in, out, in-out, ..." (the
// families once each, with their three modes, and cubic-bezier's form).
std::string easing_name_list();

}  // namespace seqc::compiler
