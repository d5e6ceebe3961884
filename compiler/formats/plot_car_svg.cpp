// The Raspblock half of plot_svg.hpp: the path from above and the outputs over time.
#include <algorithm>
#include <cmath>
#include <limits>

#include "compiler/formats/car_path.hpp"
#include "compiler/formats/plot_axes.hpp"
#include "compiler/formats/plot_song.hpp"
#include "compiler/formats/plot_svg.hpp"
#include "compiler/formats/raspblock_simulate.hpp"
#include "compiler/formats/svg_text.hpp"

namespace seqc::compiler {
namespace {

using svg::num;

// Lanes share the servo plot's left edge, so a show's performers line up on one time axis; the
// path from above sits under them.
using plot::kLeft;
using plot::kRight;
using plot::kWidth;
constexpr double kPanel = 360, kTop = 74, kLane = 70, kGap = 10;
constexpr double kLaneLeft = kLeft;
// A lane spans 400-2600 us so the outputs' whole range (500-2500) sits inside its frame.
constexpr double kLaneLow = 400, kLaneHigh = 2600;
constexpr double kPi = 3.14159265358979323846;

using Pose = CarPose;

std::string path_panel(const CarSimulation& sim, double top) {
  const std::vector<Pose> path = car_path(sim);
  double min_x = 0, max_x = 0, min_y = 0, max_y = 0;
  for (const Pose& p : path) {
    min_x = std::min(min_x, p.x), max_x = std::max(max_x, p.x);
    min_y = std::min(min_y, p.y), max_y = std::max(max_y, p.y);
  }
  const double span = std::max({max_x - min_x, max_y - min_y, 20.0});
  const double scale = (kPanel - 40) / span;
  const double cx = kLaneLeft + kPanel / 2, cy = top + kPanel / 2;
  const double mx = (min_x + max_x) / 2, my = (min_y + max_y) / 2;
  auto X = [&](double x) { return cx + (x - mx) * scale; };
  auto Y = [&](double y) { return cy - (y - my) * scale; };
  std::string out =
      svg::rect(kLaneLeft, top, kPanel, kPanel, "fill=\"#f9fafb\" stroke=\"#d1d5db\"");
  out += svg::text(12, top + 16, "path", "font-weight=\"bold\"");
  out += svg::text(12, top + 30, "from above", "fill=\"#6b7280\"");
  out += svg::text(kLaneLeft + kPanel + 12, top + 16,
                   "model: speeds integrated as 1 speed unit = 1 cm/s (x right, y forward),",
                   "fill=\"#4b5563\" font-size=\"10\"");
  out += svg::text(kLaneLeft + kPanel + 12, top + 30,
                   "z = 1 deg/s clockwise; the board's speeds are uncalibrated, so the scale is "
                   "nominal.",
                   "fill=\"#4b5563\" font-size=\"10\"");
  out += svg::text(kLaneLeft + kPanel + 12, top + 48,
                   "green: start, red: end, blue: heading each second",
                   "fill=\"#4b5563\" font-size=\"10\"");
  std::vector<double> xs, ys;
  for (const Pose& p : path) {
    xs.push_back(X(p.x));
    ys.push_back(Y(p.y));
  }
  out += svg::polylines(xs, ys, "fill=\"none\" stroke=\"#1f2937\" stroke-width=\"1.6\"");
  // Heading arrows once a second (every so many whole seconds for a long program, so that there
  // are at most kArrows): at the first sample at or after each.
  constexpr std::uint64_t kArrows = 200;
  const std::uint64_t every =
      std::max<std::uint64_t>(1, (sim.duration_ms + kArrows * 1000 - 1) / (kArrows * 1000)) * 1000;
  std::uint64_t next_arrow = 0;
  for (std::size_t i = 0; i < path.size(); ++i) {
    if (sim.samples[i].time_ms < next_arrow) continue;
    while (next_arrow <= sim.samples[i].time_ms) next_arrow += every;
    const double h = path[i].heading * kPi / 180;
    out += svg::line(X(path[i].x), Y(path[i].y), X(path[i].x) + 9 * std::sin(h),
                     Y(path[i].y) - 9 * std::cos(h), "stroke=\"#2563eb\" stroke-width=\"1.2\"");
  }
  // The scale: a bar of a round number of (nominal) centimetres, about a quarter of the panel.
  const double bar_cm = svg::nice_step(span, 4);
  const double bar_x = kLaneLeft, bar_y = top + kPanel + 14;  // under the panel, clear of the path
  out += "<g class=\"scale\"><title>scale: " + num(bar_cm) + " cm (nominal)</title>\n";
  out += svg::line(bar_x, bar_y, bar_x + bar_cm * scale, bar_y, "stroke=\"#374151\"");
  out += svg::line(bar_x, bar_y - 4, bar_x, bar_y + 4, "stroke=\"#374151\"");
  out += svg::line(bar_x + bar_cm * scale, bar_y - 4, bar_x + bar_cm * scale, bar_y + 4,
                   "stroke=\"#374151\"");
  out += svg::text(bar_x + bar_cm * scale + 6, bar_y + 4, num(bar_cm) + " cm",
                   "fill=\"#374151\" font-size=\"10\"");
  out += "</g>\n";
  out += "<g><title>start</title><circle cx=\"" + num(X(0)) + "\" cy=\"" + num(Y(0)) +
         "\" r=\"5\" fill=\"#16a34a\"/></g>\n";
  out += "<g><title>end</title><circle cx=\"" + num(xs.back()) + "\" cy=\"" + num(ys.back()) +
         "\" r=\"5\" fill=\"#dc2626\"/></g>\n";
  return out;
}

}  // namespace

std::string plot_car_program(const compiler::RaspblockProgram& program,
                             const PlotOptions& options) {
  const CarSimulation sim = simulate_car(program, car_picture_step_ms(program));
  const double duration = sim.duration_ms;
  plot::Frame f;
  f.from = options.from_ms.value_or(0);
  f.to = std::max(f.from + 1, options.to_ms.value_or(duration));
  const double from = f.from, to = f.to;
  auto x = [&](double t) { return f.x(t); };
  struct Output {
    std::string name;
    std::optional<int> (*get)(const CarState&);
  };
  const std::vector<Output> outputs = {
      {"pan", [](const CarState& s) { return s.pan; }},
      {"tilt", [](const CarState& s) { return s.tilt; }},
      {"servo1", [](const CarState& s) { return s.servos[0]; }},
      {"servo2", [](const CarState& s) { return s.servos[1]; }},
      {"servo3", [](const CarState& s) { return s.servos[2]; }},
      {"servo4", [](const CarState& s) { return s.servos[3]; }},
  };
  std::string lanes;
  double y0 = kTop;
  for (const Output& o : outputs) {
    const bool used = std::any_of(sim.samples.begin(), sim.samples.end(),
                                  [&](const CarSimulation::Sample& s) { return o.get(s.state); });
    if (!used && o.name != "pan" && o.name != "tilt") continue;
    auto y = [&](double v) { return y0 + kLane - (v - kLaneLow) / (kLaneHigh - kLaneLow) * kLane; };
    lanes += svg::rect(kLaneLeft, y0, kWidth - kLaneLeft - kRight, kLane,
                       "fill=\"none\" stroke=\"#d1d5db\"");
    lanes += svg::text(12, y0 + 16, o.name, "font-weight=\"bold\"");
    lanes += svg::text(12, y0 + 30, "us", "fill=\"#6b7280\"");
    // The value axis: the outputs' ends and centre, each with a faint line across the lane.
    for (const int v : {500, 1500, 2500}) {
      lanes += svg::line(kLaneLeft, y(v), kWidth - kRight, y(v), "stroke=\"#f3f4f6\"");
      lanes += svg::text(kLaneLeft - 6, y(v) + 3, std::to_string(v),
                         "text-anchor=\"end\" fill=\"#9ca3af\" font-size=\"9\"");
    }
    std::vector<double> xs, ys;
    for (const CarSimulation::Sample& s : sim.samples) {
      if (s.time_ms < from || s.time_ms > to) continue;
      xs.push_back(x(s.time_ms));
      const auto v = o.get(s.state);
      ys.push_back(v ? y(*v) : std::numeric_limits<double>::quiet_NaN());
    }
    lanes += svg::polylines(xs, ys, "fill=\"none\" stroke=\"#1f2937\" stroke-width=\"1.6\"");
    y0 += kLane + kGap;
  }
  const double lanes_bottom = y0 - kGap;
  // The song under the lanes, as on the arm's picture, so its beats read against the bar lines.
  const double song_lane = options.song != nullptr ? plot::kSongLane + kGap : 0;
  const double panel_top = y0 + song_lane + 40;
  lanes += plot::markers(program.timeline, f, kTop, lanes_bottom);
  lanes += plot::time_axis(f, y0 + song_lane);
  std::string body = svg::text(12, 20, options.title, "font-size=\"15\" font-weight=\"bold\"");
  if (options.song != nullptr) body += plot::song_lane(*options.song, f, lanes_bottom + kGap);
  body += plot::beat_grid(program.timeline, f, kTop, lanes_bottom + song_lane);
  body += svg::text(12, 38,
                    std::to_string(program.packets.size()) + " packets, " + num(duration / 1000.0) +
                        " s; the gimbal and servo outputs over time",
                    "fill=\"#4b5563\"");
  body += lanes + path_panel(sim, panel_top);
  return svg::document(kWidth, panel_top + kPanel + 30, options.title, body);
}

}  // namespace seqc::compiler
