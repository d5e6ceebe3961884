#include "compiler/formats/plot_svg.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <optional>

#include "compiler/formats/plot_axes.hpp"
#include "compiler/formats/simulate.hpp"
#include "compiler/formats/svg_text.hpp"

namespace seqc::backend {
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
  const double height = kTop + static_cast<double>(lanes) * (kLane + kGap) + song_lane + kAxis + 12;
  const bool pwm = program.robot.profile.rfind("lsc", 0) == 0;
  const std::string unit = pwm ? "us" : "units";
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
    const std::string band = "fill=\"#fde2e2\"><title>outside " + info->name + "'s limits " +
                             std::to_string(info->min) + "-" + std::to_string(info->max) +
                             "</title></rect";
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
  return svg::document(kWidth, height, options.title, body);
}

}  // namespace seqc::backend
