#include "compiler/formats/plot_svg.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <optional>

#include "compiler/formats/plot_axes.hpp"
#include "compiler/formats/simulate.hpp"
#include "compiler/formats/svg_text.hpp"
#include "compiler/frontend/profiles.hpp"

namespace seqc::compiler {
namespace {

using svg::num;

using plot::beat_grid;
using plot::Frame;
using plot::kLeft;
using plot::kRight;
using plot::kWidth;
using plot::markers;
using plot::time_axis;

constexpr double kTop = 74, kLane = 84, kGap = 12;
constexpr double kAxis = 40;
constexpr double kPanel = 300, kPanelTop = 34, kPanelGap = 60;  // the tip's panels

using Mm = std::array<double, 3>;

// One view of the tip's path: `h` and `v` take a point in mm to the panel's horizontal and
// vertical coordinates (mm); the same scale on both axes, so a straight line looks straight.
template <typename H, typename V>
std::string tip_panel(double left, double top, double width, const std::string& title,
                      const std::string& h_name, const std::string& v_name,
                      const std::vector<Mm>& path, const std::vector<std::vector<Mm>>& lines, H h,
                      V v) {
  double h0 = INFINITY, h1 = -INFINITY, v0 = INFINITY, v1 = -INFINITY;
  auto grow = [&](const Mm& p) {
    h0 = std::min(h0, h(p)), h1 = std::max(h1, h(p));
    v0 = std::min(v0, v(p)), v1 = std::max(v1, v(p));
  };
  for (const Mm& p : path) grow(p);
  for (const auto& l : lines) {
    for (const Mm& p : l) grow(p);
  }
  // A square window in mm around the path, at least 100 mm across, with a margin.
  const double span = std::max({h1 - h0, v1 - v0, 100.0}) * 1.1;
  const double hc = (h0 + h1) / 2, vc = (v0 + v1) / 2;
  const double size = std::min(width, kPanel);
  auto x = [&](double mm) { return left + (mm - (hc - span / 2)) / span * size; };
  auto y = [&](double mm) { return top + size - (mm - (vc - span / 2)) / span * size; };
  std::string out = "<g class=\"tip-view\"><title>" + svg::escape(title) + "</title>\n";
  out += svg::text(left, top - 10, title, "font-weight=\"bold\"");
  out += svg::rect(left, top, size, size, "fill=\"none\" stroke=\"#d1d5db\"");
  const double step = svg::nice_step(span, 5);
  for (double mm = std::ceil((hc - span / 2) / step) * step; mm <= hc + span / 2; mm += step) {
    out += svg::line(x(mm), top, x(mm), top + size, "stroke=\"#f3f4f6\"");
    out += svg::text(x(mm), top + size + 14, num(mm + 0.0),
                     "text-anchor=\"middle\" "
                     "fill=\"#6b7280\" font-size=\"9\"");
  }
  for (double mm = std::ceil((vc - span / 2) / step) * step; mm <= vc + span / 2; mm += step) {
    out += svg::line(left, y(mm), left + size, y(mm), "stroke=\"#f3f4f6\"");
    out += svg::text(left - 4, y(mm) + 3, num(mm + 0.0),
                     "text-anchor=\"end\" "
                     "fill=\"#6b7280\" font-size=\"9\"");
  }
  out += svg::text(left + size / 2, top + size + 28, h_name + " (mm)",
                   "text-anchor=\"middle\" fill=\"#4b5563\"");
  out += svg::text(left - 34, top + size / 2, v_name + " (mm)",
                   "text-anchor=\"middle\" fill=\"#4b5563\" transform=\"rotate(-90 " +
                       num(left - 34) + " " + num(top + size / 2) + ")\"");
  std::vector<double> xs, ys;
  for (const Mm& p : path) xs.push_back(x(h(p))), ys.push_back(y(v(p)));
  out += svg::polylines(xs, ys, "fill=\"none\" stroke=\"#1f2937\" stroke-width=\"1.6\"");
  for (const auto& l : lines) {
    xs.clear(), ys.clear();
    for (const Mm& p : l) xs.push_back(x(h(p))), ys.push_back(y(v(p)));
    out += svg::polylines(xs, ys,
                          "fill=\"none\" stroke=\"#2563eb\" stroke-width=\"1.4\" "
                          "stroke-dasharray=\"5 3\"");
  }
  return out + "</g>\n";
}

}  // namespace

std::string plot_servo_program(const compiler::ServoProgram& program, const PlotOptions& options) {
  const double duration = static_cast<double>(program.duration_ms());
  Frame f;
  f.from = options.from_ms.value_or(0);
  f.to = options.to_ms.value_or(duration);
  if (f.to <= f.from) f.to = f.from + 1;
  const auto step = static_cast<std::uint32_t>(std::max(1.0, std::floor((f.to - f.from) / 900)));
  const Simulation sim = simulate(program, step, true);
  const std::size_t lanes = sim.columns.size();
  const double song_lane = options.song != nullptr ? plot::kSongLane + kGap : 0;
  // The tip's path, from above and from the side, when the file placed the tip in millimetres.
  const bool tip_views = sim.with_tip && !program.timeline.tip_moves.empty();
  const double lanes_height =
      kTop + static_cast<double>(lanes) * (kLane + kGap) + song_lane + kAxis + 12;
  const double height = lanes_height + (tip_views ? kPanelTop + kPanel + kPanelGap : 0);
  const std::string unit(position_unit(program.robot.profile));
  const double lanes_bottom = kTop + static_cast<double>(lanes) * (kLane + kGap) - kGap;
  const double bottom = lanes_bottom + song_lane;

  std::string body = svg::text(12, 20, options.title, "font-size=\"15\" font-weight=\"bold\"");
  body += svg::text(12, 38,
                    std::to_string(program.keyframes.size()) + " actions, " +
                        num(duration / 1000.0) + " s; dashed: the curve as written, solid: the " +
                        "controller's motion; ticks: actions; shaded: outside the limits",
                    "fill=\"#4b5563\"");
  // The song under the grid, so its beats can be read against the file's bar lines.
  if (options.song != nullptr) body += plot::song_lane(*options.song, f, lanes_bottom + kGap);
  body += beat_grid(program.timeline, f, kTop, bottom);

  for (std::size_t lane = 0; lane < lanes; ++lane) {
    const compiler::ServoInfo* info = program.robot.find_name(sim.columns[lane]);
    if (info == nullptr) continue;
    const double y0 = kTop + static_cast<double>(lane) * (kLane + kGap);
    const double pad = std::max(1.0, (info->max - info->min) * 0.08);
    const double lo = info->min - pad, hi = info->max + pad;
    auto y = [&](double v) { return y0 + kLane - (v - lo) / (hi - lo) * kLane; };
    body += "<g class=\"lane\"><title>" + svg::escape(info->name) + "</title>\n";
    body +=
        svg::rect(kLeft, y0, kWidth - kLeft - kRight, kLane, "fill=\"none\" stroke=\"#d1d5db\"");
    const std::string band = "fill=\"#fde2e2\"><title>outside " + svg::escape(info->name) +
                             "'s limits " + std::to_string(info->min) + "-" +
                             std::to_string(info->max) + "</title></rect";
    body += "<rect x=\"" + num(kLeft) + "\" y=\"" + num(y0) + "\" width=\"" +
            num(kWidth - kLeft - kRight) + "\" height=\"" + num(y(info->max) - y0) + "\" " + band +
            ">\n";
    body += "<rect x=\"" + num(kLeft) + "\" y=\"" + num(y(info->min)) + "\" width=\"" +
            num(kWidth - kLeft - kRight) + "\" height=\"" + num(y0 + kLane - y(info->min)) + "\" " +
            band + ">\n";
    body += svg::text(12, y0 + 16, info->name, "font-weight=\"bold\"");
    body +=
        svg::text(12, y0 + 30, "id " + std::to_string(info->id) + ", " + unit, "fill=\"#6b7280\"");
    body += svg::text(kLeft - 6, y(info->max) + 4, std::to_string(info->max),
                      "text-anchor=\"end\" fill=\"#9ca3af\" font-size=\"9\"");
    body += svg::text(kLeft - 6, y(info->min) + 4, std::to_string(info->min),
                      "text-anchor=\"end\" fill=\"#9ca3af\" font-size=\"9\"");

    std::vector<double> xs, intended, compiled;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    for (const Simulation::Sample& s : sim.samples) {
      if (!f.inside(s.time_ms)) continue;
      xs.push_back(f.x(s.time_ms));
      const double want = s.intended[lane];
      intended.push_back(std::isnan(want) ? nan : y(want));
      compiled.push_back(y(s.positions[lane]));
    }
    body += svg::polylines(xs, compiled, "fill=\"none\" stroke=\"#1f2937\" stroke-width=\"1.6\"");
    body += svg::polylines(xs, intended,
                           "fill=\"none\" stroke=\"#2563eb\" stroke-width=\"1.4\" "
                           "stroke-dasharray=\"5 3\"");
    for (const compiler::Keyframe& k : program.keyframes) {
      const bool moves = std::any_of(k.targets.begin(), k.targets.end(),
                                     [&](const lsc::ServoTarget& t) { return t.id == info->id; });
      if (moves && f.inside(k.start_ms)) {
        body += svg::line(f.x(k.start_ms), y0 + kLane - 6, f.x(k.start_ms), y0 + kLane,
                          "stroke=\"#6b7280\"");
      }
    }
    body += "</g>\n";
    const std::size_t index = static_cast<std::size_t>(info - program.robot.servos.data());
    for (const compiler::TimelineWarning& w : program.timeline.warnings) {
      if (w.servo != index || !f.inside(w.at_ms)) continue;
      const double v = program.timeline.value(index, w.at_ms).value_or(info->min);
      body += "<g class=\"warning\"><title>warning: " + svg::escape(w.message) + "</title>";
      body += "<circle cx=\"" + num(f.x(w.at_ms)) + "\" cy=\"" + num(y(v)) +
              "\" r=\"5\" fill=\"#f59e0b\" stroke=\"#92400e\"/></g>\n";
    }
  }
  body += markers(program.timeline, f, kTop, bottom);
  body += time_axis(f, bottom + 8);
  if (tip_views) {
    // The controller's motion, as `simulate` computes it, and each `path: line` move's line,
    // sampled so that the side view (distance from the base axis against height) shows the
    // curve a straight line makes there.
    std::vector<Mm> path;
    for (const Simulation::Sample& s : sim.samples) {
      if (f.inside(s.time_ms)) path.push_back(s.tip);
    }
    std::vector<std::vector<Mm>> lines;
    for (const compiler::TimelineTipMove& m : program.timeline.tip_moves) {
      if (!m.line || m.end_ms < f.from || m.start_ms > f.to) continue;
      std::vector<Mm> l;
      for (int i = 0; i <= 64; ++i) {
        const double u = i / 64.0;
        l.push_back({m.from[0] + (m.to[0] - m.from[0]) * u, m.from[1] + (m.to[1] - m.from[1]) * u,
                     m.from[2] + (m.to[2] - m.from[2]) * u});
      }
      lines.push_back(std::move(l));
    }
    const double top = lanes_height + kPanelTop;
    const double half = (kWidth - kLeft - kRight) / 2;
    body += svg::text(12, top - 10, "the tip", "font-weight=\"bold\"");
    body += svg::text(12, top + 6, "solid: as the", "fill=\"#6b7280\"");
    body += svg::text(12, top + 20, "controller moves;", "fill=\"#6b7280\"");
    body += svg::text(12, top + 34, "dashed: path: line", "fill=\"#6b7280\"");
    body += tip_panel(
        kLeft, top, half - 40, "from above", "x", "y", path, lines,
        [](const Mm& p) { return p[0]; }, [](const Mm& p) { return p[1]; });
    body += tip_panel(
        kLeft + half + 20, top, half - 40, "from the side", "r (from the base axis)", "z", path,
        lines, [](const Mm& p) { return std::hypot(p[0], p[1]); },
        [](const Mm& p) { return p[2]; });
  }
  return svg::document(kWidth, height, options.title, body);
}

}  // namespace seqc::compiler
