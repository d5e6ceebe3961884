#include "compiler/formats/plot_axes.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>

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

std::string markers(const compiler::Timeline& tl, const Frame& f, double top, double bottom) {
  std::string out;
  int row = 0;
  for (const compiler::TimelineMarker& m : tl.markers) {
    const double t = m.at.value();
    if (!f.inside(t)) continue;
    const bool section = m.label.rfind("section ", 0) == 0;
    const char* colour =
        section ? "#7c3aed" : (m.label.rfind("at ", 0) == 0 ? "#0e7490" : "#b45309");
    out += "<g class=\"marker\"><title>" + svg::escape(m.label) + "</title>\n";
    out += svg::line(f.x(t), top - 20 + 10.0 * (row % 2), f.x(t), bottom,
                     std::string("stroke=\"") + colour + "\" stroke-dasharray=\"4 3\"");
    out += svg::text(f.x(t) + 3, top - 22 + 10.0 * (row % 2), m.label,
                     std::string("fill=\"") + colour + "\" font-size=\"10\"");
    out += "</g>\n";
    ++row;
  }
  return out;
}

}  // namespace seqc::compiler::plot
