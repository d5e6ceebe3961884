#include "compiler/backend/plot_svg.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <optional>

#include "compiler/backend/simulate.hpp"
#include "compiler/backend/svg_text.hpp"

namespace seqc::backend {
namespace {

using svg::num;

constexpr double kWidth = 1100, kLeft = 150, kRight = 24, kTop = 74, kLane = 84, kGap = 12;
constexpr double kAxis = 40;

struct Frame {  // time window -> x
  double from = 0, to = 1;
  double x(double t) const { return kLeft + (t - from) / (to - from) * (kWidth - kLeft - kRight); }
  bool inside(double t) const { return t >= from && t <= to; }
};

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
  const double height = kTop + static_cast<double>(lanes) * (kLane + kGap) + kAxis + 12;
  const bool pwm = program.robot.profile.rfind("lsc", 0) == 0;
  const std::string unit = pwm ? "us" : "units";
  const double bottom = kTop + static_cast<double>(lanes) * (kLane + kGap) - kGap;

  std::string body = svg::text(12, 20, options.title, "font-size=\"15\" font-weight=\"bold\"");
  body += svg::text(12, 38,
                    std::to_string(program.keyframes.size()) + " actions, " +
                        num(duration / 1000.0) + " s; dashed: the curve as written, solid: the " +
                        "controller's motion; ticks: actions; shaded: outside the limits",
                    "fill=\"#4b5563\"");
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
