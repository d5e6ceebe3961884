#include "compiler/formats/preview_html.hpp"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <initializer_list>
#include <optional>
#include <string_view>
#include <utility>

#include "base/json_text.hpp"
#include "compiler/formats/car_path.hpp"
#include "compiler/formats/plot_svg.hpp"
#include "compiler/formats/preview_page_text.hpp"
#include "compiler/formats/raspblock_simulate.hpp"
#include "compiler/formats/svg_text.hpp"
#include "compiler/frontend/profiles.hpp"
#include "compiler/targets/servo_controller/servo_wire.hpp"

namespace seqc::compiler {
namespace {

using seqc::json_string;
using svg::num;

// The plot picture as inline SVG in HTML: without the XML namespace attribute (HTML puts an
// <svg> in its namespace itself, and the page then names no URL at all), with a playhead the
// script moves.
std::string lanes_for_page(std::string svg) {
  const std::string ns = " xmlns=\"http://www.w3.org/2000/svg\"";
  if (const auto at = svg.find(ns); at != std::string::npos) svg.erase(at, ns.size());
  const auto h = svg.find("height=\"");
  const std::string height =
      h == std::string::npos ? "100" : svg.substr(h + 8, svg.find('"', h + 8) - h - 8);
  const auto end = svg.rfind("</svg>");
  if (end != std::string::npos) {
    svg.insert(end, "<line class=\"playhead\" x1=\"150\" y1=\"44\" x2=\"150\" y2=\"" + height +
                        "\" stroke=\"#dc2626\" stroke-width=\"1.5\"/>\n");
  }
  return svg;
}

// "bars":[ms...],"beats":[ms...]: where each bar and each beat starts, from the tempo map, as
// the plot's ruler numbers them.
std::string bars_json(const compiler::Timeline& tl, double end_ms) {
  const compiler::TempoMap& map = tl.tempo_map;
  std::string bars = "[", beats = "[";
  if (std::any_of(map.changes().begin(), map.changes().end(),
                  [](const compiler::TempoMap::Change& c) { return c.bpm > 0; })) {
    for (std::int64_t beat = 0; beat < 100000; ++beat) {
      const std::optional<compiler::ExactMs> at = map.time_of_beat(beat);
      if (!at || at->value() > end_ms) break;
      beats += (beats.size() > 1 ? "," : "") + num(at->value());
      if (map.meter_at(*at) > 0 && map.bar_of_beat(beat).den() == 1) {
        bars += (bars.size() > 1 ? "," : "") + num(at->value());
      }
    }
  }
  return "\"bars\":" + bars + "],\"beats\":" + beats + "]";
}

PlotOptions window(const std::string& title, double end_ms) {
  PlotOptions options;
  options.title = title;
  options.from_ms = 0;
  options.to_ms = std::max(end_ms, 1.0);
  return options;
}

std::string joint_json(const compiler::ArmJoint& j) {
  return "{\"servo\":" + json_string(j.servo) + ",\"zero\":" + num(j.zero) +
         ",\"sign\":" + std::to_string(j.sign) + "}";
}

// The data for a <script type="application/json"> element. HTML ends that element at the first
// "</script" and reads "<!--" as an escape that can hide the end, so no <, > or & may appear in
// it: each is written as a JSON escape, as are U+2028 and U+2029 (line ends to a JavaScript
// reader of old). Outside strings JSON has none of these, so the whole text can be rewritten
// and parses to the same value.
std::string script_safe(std::string_view json) {
  std::string out;
  out.reserve(json.size());
  for (std::size_t i = 0; i < json.size(); ++i) {
    const char c = json[i];
    if (c == '<') {
      out += "\\u003c";
    } else if (c == '>') {
      out += "\\u003e";
    } else if (c == '&') {
      out += "\\u0026";
    } else if (json.substr(i, 3) == "\xE2\x80\xA8" || json.substr(i, 3) == "\xE2\x80\xA9") {
      out += json[i + 2] == '\xA8' ? "\\u2028" : "\\u2029";
      i += 2;
    } else {
      out += c;
    }
  }
  return out;
}

// The skeleton with each @name@ of `parts` replaced by its text. Only the skeleton is scanned: an
// "@" in a part (a title, the data) is copied as it is.
std::string fill(std::string_view skeleton,
                 std::initializer_list<std::pair<std::string_view, std::string_view>> parts) {
  std::size_t size = skeleton.size();
  for (const auto& part : parts) size += part.second.size();
  std::string out;
  out.reserve(size);
  std::size_t from = 0;
  for (std::size_t at = skeleton.find('@'); at != std::string_view::npos;
       at = skeleton.find('@', at + 1)) {
    const std::size_t close = skeleton.find('@', at + 1);
    if (close == std::string_view::npos) break;
    const std::string_view name = skeleton.substr(at + 1, close - at - 1);
    const auto part =
        std::find_if(parts.begin(), parts.end(), [&](const auto& p) { return p.first == name; });
    if (part == parts.end()) continue;
    out.append(skeleton.substr(from, at - from)).append(part->second);
    from = close + 1;
    at = close;
  }
  return out.append(skeleton.substr(from));
}

// RFC 4648 base64, for the song's data: URL.
std::string base64(const std::string& bytes) {
  static constexpr char kAlphabet[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::size_t n = std::min<std::size_t>(3, bytes.size() - i);
    std::uint32_t v = 0;
    for (std::size_t k = 0; k < 3; ++k) {
      v = (v << 8) | (k < n ? static_cast<unsigned char>(bytes[i + k]) : 0u);
    }
    for (std::size_t k = 0; k < 4; ++k) {
      out += k <= n ? kAlphabet[(v >> (18 - 6 * k)) & 63] : '=';
    }
  }
  return out;
}

}  // namespace

std::string audio_mime(const std::string& path) {
  const auto dot = path.rfind('.');
  std::string ext = dot == std::string::npos ? "" : path.substr(dot + 1);
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext == "wav") return "audio/wav";
  if (ext == "flac") return "audio/flac";
  if (ext == "ogg" || ext == "oga" || ext == "opus") return "audio/ogg";
  if (ext == "mp3") return "audio/mpeg";
  return "";
}

PreviewPart preview_servo_part(const compiler::ServoProgram& program, const std::string& title,
                               double end_ms, const PlotSong* song) {
  const compiler::RobotInfo& robot = program.robot;
  std::string j = "{\"kind\":\"servo\",\"title\":" + json_string(title) +
                  ",\"duration\":" + std::to_string(program.duration_ms()) + ",\"unit\":" + "\"" +
                  std::string(position_unit(robot.profile)) + "\"" + ",\"servos\":[";
  for (std::size_t i = 0; i < robot.servos.size(); ++i) {
    const compiler::ServoInfo& s = robot.servos[i];
    j += std::string(i ? "," : "") + "{\"name\":" + json_string(s.name) +
         ",\"id\":" + std::to_string(s.id) + ",\"min\":" + std::to_string(s.min) +
         ",\"max\":" + std::to_string(s.max) + ",\"home\":" + std::to_string(s.home) + "}";
  }
  // The servos the program moves, ascending id: simulate's columns and seqc-state's keys.
  j += "],\"columns\":[";
  bool first = true;
  for (std::uint8_t id : used_servo_ids(program)) {
    const compiler::ServoInfo* s = robot.find_id(id);
    j += std::string(first ? "" : ",") +
         json_string(s != nullptr ? s->name : "servo" + std::to_string(id));
    first = false;
  }
  // Actions as [start, time, [[servo index, target], ...]].
  j += "],\"actions\":[";
  for (std::size_t k = 0; k < program.keyframes.size(); ++k) {
    const compiler::Keyframe& key = program.keyframes[k];
    j += std::string(k ? "," : "") + "[" + std::to_string(key.start_ms) + "," +
         std::to_string(key.time_ms) + ",[";
    for (std::size_t t = 0; t < key.targets.size(); ++t) {
      const compiler::ServoInfo* s = robot.find_id(key.targets[t].id);
      const std::size_t index =
          s != nullptr ? static_cast<std::size_t>(s - robot.servos.data()) : 0;
      j += std::string(t ? "," : "") + "[" + std::to_string(index) + "," +
           std::to_string(key.targets[t].position) + "]";
    }
    j += "]]";
  }
  j += "],\"arm\":";
  if (robot.arm) {
    const compiler::ArmGeometry& a = *robot.arm;
    j += "{\"base_height\":" + num(a.base_height) + ",\"upper_arm\":" + num(a.upper_arm) +
         ",\"forearm\":" + num(a.forearm) + ",\"hand\":" + num(a.hand) +
         ",\"degrees_per_unit\":" + std::to_string(a.degrees_per_unit) +
         ",\"joints\":{\"base\":" + joint_json(a.base) + ",\"shoulder\":" + joint_json(a.shoulder) +
         ",\"elbow\":" + joint_json(a.elbow) + ",\"wrist\":" + joint_json(a.wrist) +
         "},\"claw\":" + json_string(a.claw) + "}";
  } else {
    j += "null";
  }
  j += "," + bars_json(program.timeline, end_ms) + "}";
  PlotOptions options = window(title, end_ms);
  options.song = song;
  return {j, lanes_for_page(plot_servo_program(program, options))};
}

PreviewPart preview_car_part(const compiler::RaspblockProgram& program, const std::string& title,
                             double end_ms) {
  // The state at every millisecond, kept where it changes: the page looks up the last change at
  // or before its instant, as `seqc simulate` samples it.
  const CarSimulation fine = car_changes(program);
  std::string j = "{\"kind\":\"car\",\"title\":" + json_string(title) +
                  ",\"duration\":" + std::to_string(fine.duration_ms) + ",\"changes\":[";
  auto opt = [](const std::optional<int>& v) { return v ? std::to_string(*v) : "null"; };
  bool used[4] = {};  // servo1..servo4
  const CarState* last = nullptr;
  for (const CarSimulation::Sample& s : fine.samples) {
    if (last != nullptr && s.state == *last) continue;
    const CarState& c = s.state;
    j += std::string(last ? "," : "") + "[" + std::to_string(s.time_ms) + "," + opt(c.pan) + "," +
         opt(c.tilt) + "," + opt(c.servos[0]) + "," + opt(c.servos[1]) + "," + opt(c.servos[2]) +
         "," + opt(c.servos[3]) + "]";
    for (std::size_t i = 0; i < 4; ++i) used[i] |= c.servos[i].has_value();
    last = &s.state;
  }
  // The outputs in simulate's column order; pan and tilt always, as the plot's lanes.
  j += "],\"outputs\":[\"pan\",\"tilt\"";
  for (int i = 0; i < 4; ++i) {
    if (used[i]) j += ",\"servo" + std::to_string(i + 1) + "\"";
  }
  // The path as `seqc plot` integrates it (20 ms samples, coarser for a long program), in mm.
  const CarSimulation coarse = simulate_car(program, car_picture_step_ms(program));
  const std::vector<CarPose> path = car_path(coarse);
  j += "],\"path\":[";
  for (std::size_t i = 0; i < path.size(); ++i) {
    j += std::string(i ? "," : "") + "[" + std::to_string(coarse.samples[i].time_ms) + "," +
         num(path[i].x * 10) + "," + num(path[i].y * 10) + "," + num(path[i].heading) + "]";
  }
  j += "]," + bars_json(program.timeline, end_ms) + "}";
  return {j, lanes_for_page(plot_car_program(program, window(title, end_ms)))};
}

std::string preview_page(const std::string& title, const std::vector<std::string>& names,
                         const std::vector<PreviewPart>& parts, double end_ms,
                         const PreviewSong* song) {
  std::string data =
      "{\"title\":" + json_string(title) + ",\"end\":" + num(end_ms) + ",\"show\":" +
      (names.size() > 1 || (!names.empty() && !names[0].empty()) ? "true" : "false") +
      ",\"parts\":[";
  for (std::size_t i = 0; i < parts.size(); ++i) {
    std::string part = parts[i].data_json;
    part.insert(1, "\"name\":" + json_string(i < names.size() ? names[i] : "") + ",");
    data += (i ? "," : "") + part;
  }
  data += "]";
  const bool plays = song != nullptr && song->missing.empty();
  if (plays) data += ",\"song\":{\"downbeat\":" + num(song->downbeat_s) + "}";
  data += "}";
  std::string audio;
  if (plays) {
    const std::string src = song->url.empty()
                                ? "data:" + song->mime + ";base64," + base64(song->bytes)
                                : svg::escape(song->url);
    audio = "<audio id=\"song\" preload=\"auto\" src=\"" + src + "\"></audio>\n";
  } else if (song != nullptr) {
    audio = "<p class=\"song-missing\">" + svg::escape(song->missing) + "</p>\n";
  }
  std::string lanes;
  for (const PreviewPart& p : parts) lanes += "<div class=\"lanes\">\n" + p.lanes_svg + "</div>\n";
  const std::string escaped_title = svg::escape(title), end = num(end_ms), safe = script_safe(data);
  return fill(preview_skeleton(), {{"title", escaped_title},
                                   {"style", preview_style()},
                                   {"end", end},
                                   {"audio", audio},
                                   {"lanes", lanes},
                                   {"data", safe},
                                   {"script", preview_script()}});
}

}  // namespace seqc::compiler
