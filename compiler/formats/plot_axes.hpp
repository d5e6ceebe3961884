// What every `seqc plot` lane picture shares, so a show's performers line up on one time axis:
// the page's width and the lanes' left and right edges, the time window mapped to x, the
// bar/beat grid from the program's tempo map (bar numbers counted across meter changes), the
// time axis in seconds, and the labelled markers (sections, `at:` cues, tempo and meter
// changes). Pure text out; nothing here knows which robot drew the lanes.
#pragma once

#include <string>
#include <string_view>

#include "compiler/timeline/timeline.hpp"

namespace seqc::compiler::plot {

inline constexpr double kWidth = 1100, kLeft = 150, kRight = 24;

struct Frame {  // time window -> x
  double from = 0, to = 1;
  double x(double t) const { return kLeft + (t - from) / (to - from) * (kWidth - kLeft - kRight); }
  bool inside(double t) const { return t >= from && t <= to; }
};

// Beat lines, darker bar lines and bar numbers from `top` to `bottom`; "" without a tempo.
std::string beat_grid(const compiler::Timeline& tl, const Frame& f, double top, double bottom);
// The axis line at `y` with a tick and a label ("1.5 s") every nice step.
std::string time_axis(const Frame& f, double y);
// How wide a label is taken to be: its characters (code points) x font size x kCharWidth, a
// sans-serif average; labels closer than kLabelGap count as overlapping.
inline constexpr double kCharWidth = 0.6, kLabelGap = 2, kMarkerFontSize = 10;
double label_width(std::string_view text, double font_size);
// Each marker inside the window as a dashed line with its label, in two rows taken in turn; a
// label that would overlap one already drawn goes to the other row, and one that fits in
// neither is left out (the line's <title> still names it), with "N labels hidden" in the left
// margin.
std::string markers(const compiler::Timeline& tl, const Frame& f, double top, double bottom);

}  // namespace seqc::compiler::plot
