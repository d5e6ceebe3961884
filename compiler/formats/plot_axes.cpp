#include "compiler/formats/plot_axes.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "compiler/formats/svg_text.hpp"

namespace seqc::compiler::plot {

using svg::num;

// Beat and bar lines from the tempo map the front end built (the file's tempo and meter and
// their changes), with bar numbers counted across meter changes.
std::string beat_grid(const compiler::Timeline& tl, const Frame& f, double top, double bottom) {
  const compiler::TempoMap& map = tl.tempo_map;
  if (std::none_of(map.changes().begin(), map.changes().end(),
                   [](const compiler::TempoMap::Change& c) { return c.bpm > 0; })) {
    return "";
  }
  std::string out = "<g class=\"grid\">\n";
  const double end = std::max(f.to, tl.end.value());
  for (std::int64_t beat = 0; beat < 100000; ++beat) {
    const std::optional<compiler::ExactMs> at = map.time_of_beat(beat);
    if (!at || at->value() > end) break;
    const double t = at->value();
    const compiler::ExactMs bar = map.bar_of_beat(beat);
    const bool bar_line = map.meter_at(*at) > 0 && bar.den() == 1;
    if (f.inside(t)) {
      out += svg::line(f.x(t), top, f.x(t), bottom,
                       bar_line ? "stroke=\"#b0b8c8\" stroke-width=\"1\""
                                : "stroke=\"#e4e8ef\" stroke-width=\"1\"");
      if (bar_line) {
        out += svg::text(f.x(t) + 2, top - 4, std::to_string(bar.num() + 1),
                         "fill=\"#6b7280\" font-size=\"9\"");
      }
    }
  }
  return out + "</g>\n";
}

std::string time_axis(const Frame& f, double y) {
  std::string out = svg::line(kLeft, y, kWidth - kRight, y, "stroke=\"#374151\"");
  const double step = svg::nice_step((f.to - f.from) / 1000.0, 10) * 1000.0;
  for (double t = std::ceil(f.from / step) * step; t <= f.to + 1e-6; t += step) {
    out += svg::line(f.x(t), y, f.x(t), y + 5, "stroke=\"#374151\"");
    out += svg::text(f.x(t), y + 17, num(t / 1000.0) + " s",
                     "text-anchor=\"middle\" fill=\"#374151\"");
  }
  return out;
}

double label_width(std::string_view text, double font_size) {
  std::size_t chars = 0;  // code points: a UTF-8 continuation byte starts none
  for (const char c : text) chars += (static_cast<unsigned char>(c) & 0xC0) != 0x80 ? 1 : 0;
  return static_cast<double>(chars) * font_size * kCharWidth;
}

std::string markers(const compiler::Timeline& tl, const Frame& f, double top, double bottom) {
  // Each label keeps the row the alternation gives it unless it would overlap a label already
  // in that row; then it takes the other row, and when both are taken it is not drawn (its
  // line and its <title> stay). A long piece with a section every bar or two would otherwise
  // print its labels over one another.
  struct Span {
    double left, right;
  };
  std::array<std::vector<Span>, 2> rows;
  auto fits = [&](int row, const Span& s) {
    return std::none_of(rows[row].begin(), rows[row].end(), [&](const Span& o) {
      return s.left < o.right + kLabelGap && o.left < s.right + kLabelGap;
    });
  };
  std::string out;
  std::size_t hidden = 0;
  int count = 0;
  for (const compiler::TimelineMarker& m : tl.markers) {
    const double t = m.at.value();
    if (!f.inside(t)) continue;
    const bool section = m.label.rfind("section ", 0) == 0;
    const char* colour =
        section ? "#7c3aed" : (m.label.rfind("at ", 0) == 0 ? "#0e7490" : "#b45309");
    const int preferred = count++ % 2;
    const Span span{f.x(t) + 3, f.x(t) + 3 + label_width(m.label, kMarkerFontSize)};
    int row = -1;
    for (const int r : {preferred, 1 - preferred}) {
      if (fits(r, span)) {
        row = r;
        break;
      }
    }
    out += "<g class=\"marker\"><title>" + svg::escape(m.label) + "</title>\n";
    out += svg::line(f.x(t), top - 20 + 10.0 * (row < 0 ? preferred : row), f.x(t), bottom,
                     std::string("stroke=\"") + colour + "\" stroke-dasharray=\"4 3\"");
    if (row >= 0) {
      rows[row].push_back(span);
      out += svg::text(span.left, top - 22 + 10.0 * row, m.label,
                       std::string("fill=\"") + colour + "\" font-size=\"10\"");
    } else {
      ++hidden;
    }
    out += "</g>\n";
  }
  if (hidden > 0) {
    // In the left margin beside the rows, where no marker's label goes.
    out += svg::text(12, top - 12,
                     std::to_string(hidden) + (hidden == 1 ? " label" : " labels") + " hidden",
                     "class=\"hidden-labels\" fill=\"#6b7280\" font-size=\"10\"");
  }
  return out;
}

}  // namespace seqc::compiler::plot
