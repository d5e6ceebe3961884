// textDocument/hover: what the name under the cursor stands for, in Markdown: a pose's values,
// a section's parameters and length, a servo's range and speed from the robot's profile, an
// easing's shape in words, a step's start, end and the tempo there.
#include <cmath>
#include <cstdio>
#include <string>

#include "compiler/frontend/profiles.hpp"
#include "compiler/timeline/easing.hpp"
#include "runtime/lsp/feature_parts.hpp"

namespace seqc::lsp {

using compiler::YamlNode;
using nlohmann::json;

namespace {

// `{claw: 300, elbow: 650}` as one line of text (nested values shortened).
std::string flat_text(const YamlNode& node) {
  if (node.is_scalar()) return node.scalar;
  std::string out;
  if (node.is_map()) {
    for (const compiler::YamlEntry& e : node.entries) {
      out += (out.empty() ? "" : ", ") + e.first.scalar + ": " +
             (e.second.is_scalar() ? e.second.scalar : std::string("..."));
    }
    return "{" + out + "}";
  }
  if (node.is_sequence()) {
    for (const YamlNode& item : node.items) {
      out += (out.empty() ? "" : ", ") + (item.is_scalar() ? item.scalar : std::string("..."));
    }
    return "[" + out + "]";
  }
  return "";
}

std::string number_text(double v) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.2f", v);
  std::string s = buf;
  while (s.back() == '0') s.pop_back();
  if (s.back() == '.') s.pop_back();
  return s;
}

std::string tempo_text(const compiler::TempoMap& map, compiler::ExactMs t) {
  if (map.bpm_at(t) <= 0) return "no tempo set";
  std::string text = "tempo " + number_text(map.bpm_at(t)) + " bpm";
  if (map.meter_at(t) > 0) {
    text +=
        ", meter " + std::to_string(map.meter_at(t)) + "/" + std::to_string(map.beat_unit_at(t));
  }
  return text;
}

std::string easing_words(const std::string& name) {
  const compiler::EaseParse parsed = compiler::parse_easing(name);
  if (!parsed.easing) return "";
  const compiler::Easing& e = *parsed.easing;
  using compiler::EaseFamily;
  using compiler::EaseMode;
  if (e.family == EaseFamily::Linear) return "a straight line: the same speed all the way";
  if (e.family == EaseFamily::Bezier) {
    return "a CSS cubic Bézier curve with control points (" + number_text(e.x1) + ", " +
           number_text(e.y1) + ") and (" + number_text(e.x2) + ", " + number_text(e.y2) + ")";
  }
  std::string how;
  switch (e.mode) {
    case EaseMode::In:
      how = "starts slowly and speeds up to the end";
      break;
    case EaseMode::Out:
      how = "starts fast and slows down into the end";
      break;
    case EaseMode::InOut:
      how = "starts and ends slowly, fastest halfway";
      break;
  }
  std::string curve;
  switch (e.family) {
    case EaseFamily::Quad:
      curve = "a gentle power curve (t\u00B2)";
      break;
    case EaseFamily::Cubic:
      curve = "a power curve (t\u00B3)";
      break;
    case EaseFamily::Quart:
      curve = "a steep power curve (t\u2074)";
      break;
    case EaseFamily::Quint:
      curve = "a very steep power curve (t\u2075)";
      break;
    case EaseFamily::Sine:
      curve = "a quarter sine wave, the softest";
      break;
    case EaseFamily::Expo:
      curve = "an exponential curve, nearly still at its slow end";
      break;
    case EaseFamily::Circ:
      curve = "a quarter circle, vertical at its fast end";
      break;
    case EaseFamily::Back:
      curve = "overshoots by about 10 % (pulls back before or past the end)";
      break;
    case EaseFamily::Elastic:
      curve = "springs like a plucked string, past its ends";
      break;
    case EaseFamily::Bounce:
      curve = "bounces four times, like a dropped ball";
      break;
    default:
      break;
  }
  return how + "; " + curve;
}

std::string pose_hover(const Analysis& a, const Name& n) {
  const Name* def = a.definition_of(n);
  std::string text = "**pose** `" + n.text + "`\n\n";
  if (def == nullptr || def->node == nullptr) {
    if (n.text == "home") return text + "built in: every named servo to its home position";
    return text + "not defined in this file or the files it includes";
  }
  text += "`" + flat_text(*def->node) + "`";
  if (def->span.file != n.span.file) text += "\n\nfrom " + a.sources().path(def->span.file);
  return text;
}

std::string section_hover(const Analysis& a, const Name& n) {
  const Name* def = a.definition_of(n);
  std::string text = "**section** `" + n.text + "`";
  if (def != nullptr && def->node != nullptr && def->node->is_map()) {
    if (const YamlNode* params = def->node->find("params"); params && params->is_map()) {
      text += "\n\nparameters:";
      for (const compiler::YamlEntry& p : params->entries) {
        text += " `" + p.first.scalar + ": " + flat_text(p.second) + "`";
      }
    }
  }
  if (const compiler::StepTime* t = section_performance(a, n.text)) {
    text += "\n\nlength " + duration_text(t->end - t->start);
    const compiler::TempoMap& map = a.tempo_map();
    if (map.bpm_at(t->start) > 0) {
      text += " (" + number_text((map.beat_at(t->end) - map.beat_at(t->start)).value()) + " beats)";
    }
    text += "; first performed at " + instant_text(map, t->start);
  } else if (a.walked()) {
    text += "\n\nnot performed";
  }
  return text;
}

std::string servo_hover(const Analysis& a, const Name& n) {
  const auto& robot = a.robot();
  std::string text = "**servo** `" + n.text + "`";
  if (!robot) return text;
  const auto it = robot->names.find(n.text);
  if (it == robot->names.end() || it->second >= robot->info.servos.size()) {
    return text + "\n\nnot a servo of this robot";
  }
  const compiler::ServoInfo& s = robot->info.servos[it->second];
  const compiler::RobotProfile* profile = robot->profile;
  const std::string unit =
      profile ? std::string(compiler::position_unit(profile->name)) : std::string("units");
  text += " (id " + std::to_string(s.id) + ")\n\nrange " + std::to_string(s.min) + "\u2013" +
          std::to_string(s.max) + " " + unit + ", home " + std::to_string(s.home);
  if (profile != nullptr && profile->units_per_degree > 0) {
    const auto deg = [&](int u) {
      return number_text((u - profile->degree_zero) / profile->units_per_degree);
    };
    text += " (" + deg(s.min) + "\u2013" + deg(s.max) + "\u00B0)";
  }
  if (s.max_speed) {
    text += "\n\nmax speed " + number_text(*s.max_speed) + "/s";
    if (profile != nullptr && profile->units_per_degree > 0) {
      text += " (" + number_text(*s.max_speed / profile->units_per_degree) + "\u00B0/s)";
    }
  }
  if (s.max_accel) text += ", max accel " + number_text(*s.max_accel) + "/s\u00B2";
  return text;
}

std::string step_hover(const Analysis& a, const Name& n) {
  const compiler::StepTime* t = n.node ? a.times().find(n.node->location) : nullptr;
  std::string text = "**step** `" + n.text + "`";
  if (t == nullptr) return text + (a.walked() ? "\n\nnot walked" : "");
  const compiler::TempoMap& map = a.tempo_map();
  text += "\n\nstarts " + instant_text(map, t->start) + ", ends " + instant_text(map, t->end) +
          " (" + duration_text(t->end - t->start) + ")";
  if (a.downbeat()) text += "; " + seconds_text(*a.downbeat() + t->start) + " into the song";
  text += "\n\n" + tempo_text(map, t->start);
  if (t->performances > 1) {
    text += "\n\nperformed " + std::to_string(t->performances) + " times (the first shown)";
  }
  return text;
}

std::string param_hover(const Analysis& a, const Name& n) {
  std::string text = "**parameter** `$" + n.text + "` of section `" + n.section + "`";
  const Name* def = a.definition_of(n);
  if (def != nullptr && def->node != nullptr) text += "\n\ndefault `" + flat_text(*def->node) + "`";
  return text;
}

}  // namespace

const compiler::StepTime* section_performance(const Analysis& a, const std::string& name) {
  for (const Name& m : a.names()) {
    if (m.kind != NameKind::Step || m.text != "section" || m.node == nullptr) continue;
    const YamlNode* value = m.node->find("section");
    if (value == nullptr || value->scalar != name) continue;
    if (const compiler::StepTime* t = a.times().find(m.node->location)) return t;
  }
  return nullptr;
}

json hover(Request& r) {
  if (!r.position) return nullptr;
  const Analysis& a = *r.analysis;
  const Name* n = a.name_at(*r.file, *r.position);
  if (n == nullptr) return nullptr;
  std::string text;
  switch (n->kind) {
    case NameKind::Pose:
      text = pose_hover(a, *n);
      break;
    case NameKind::Section:
      text = section_hover(a, *n);
      break;
    case NameKind::Servo:
      text = servo_hover(a, *n);
      break;
    case NameKind::Easing:
      text = "**easing** `" + n->text + "`";
      if (const std::string words = easing_words(n->text); !words.empty()) text += "\n\n" + words;
      break;
    case NameKind::Step:
      text = step_hover(a, *n);
      break;
    case NameKind::Param:
      text = param_hover(a, *n);
      break;
    case NameKind::Group: {
      const Name* def = a.definition_of(*n);
      text = "**group** `" + n->text + "`";
      if (def != nullptr && def->node != nullptr) text += "\n\n`" + flat_text(*def->node) + "`";
      break;
    }
    case NameKind::Include:
      text = "**include** `" + n->target + "`";
      break;
  }
  return {{"contents", {{"kind", "markdown"}, {"value", text}}}, {"range", range_json(a, n->span)}};
}

}  // namespace seqc::lsp
