#include "compiler/formats/listing.hpp"
#include "base/json_text.hpp"
#include "base/terminal_text.hpp"

#include <fmt/format.h>

#include "base/units.hpp"

namespace seqc::compiler {
using seqc::json_string;
namespace {

std::string servo_label(const compiler::ServoProgram& program, std::uint8_t id) {
  const compiler::ServoInfo* s = program.robot.find_id(id);
  return s != nullptr ? fmt::format("{}({})", seqc::terminal_safe(s->name), id)
                      : fmt::format("servo({})", id);
}

}  // namespace

std::string location_text(const seqc::Location& at, const seqc::SourceManager& sources) {
  if (at.line == 0 || at.file >= sources.file_count()) return "";
  return fmt::format("{}:{}:{}", sources.path(at.file), at.line, at.column);
}

std::string render_hex(const std::vector<PlannedFrame>& plan) {
  std::string out;
  for (const PlannedFrame& p : plan) out += to_hex(p.bytes) + "\n";
  return out;
}

std::string render_listing(const compiler::ServoProgram& program,
                           const std::vector<PlannedFrame>& plan, std::uint8_t group,
                           const seqc::SourceManager& sources, std::string_view storage) {
  const std::size_t n = program.keyframes.size();
  std::string out = fmt::format("# robot {}, group {}: {} action{}{}, {} frames, {}\n",
                                program.robot.profile, group, n, n == 1 ? "" : "s", storage,
                                plan.size(), seqc::format_seconds(program.duration_ms()));
  for (std::size_t i = 0; i < plan.size(); ++i) {
    const PlannedFrame& p = plan[i];
    out += fmt::format("frame {}: {}\n", i + 1, to_hex(p.bytes));
    out += fmt::format("  header 55 55 | len {} | cmd {:02x} | {}\n", p.bytes.size() - 2,
                       p.bytes[3], p.fields);
    if (!p.keyframe) continue;
    const compiler::Keyframe& k = program.keyframes[*p.keyframe];
    // An action no step wrote (the hold before an `at:` cue) says so rather than "from :".
    const std::string from = seqc::terminal_safe(location_text(k.source, sources));
    if (k.targets.empty()) {
      // An action naming no servo is an opening rest: every servo stays where it stands.
      out += fmt::format("  action {} at {} ms, a rest (no servo named)\n", *p.keyframe + 1,
                         k.start_ms);
      continue;
    }
    out += from.empty()
               ? fmt::format("  action {} at {} ms, a hold:", *p.keyframe + 1, k.start_ms)
               : fmt::format("  action {} at {} ms from {}:", *p.keyframe + 1, k.start_ms, from);
    for (const lsc::ServoTarget& t : k.targets) {
      out += fmt::format(" {}={}", servo_label(program, t.id), t.position);
    }
    out += "\n";
  }
  return out;
}

std::string render_json(const compiler::ServoProgram& program,
                        const std::vector<PlannedFrame>& plan, std::uint8_t group,
                        const seqc::SourceManager& sources) {
  std::string out = "{\n";
  out += fmt::format("  \"robot\": {},\n  \"group\": {},\n  \"duration_ms\": {},\n",
                     json_string(program.robot.profile), group, program.duration_ms());
  out += "  \"servos\": [";
  const std::vector<std::uint8_t> used = used_servo_ids(program);
  for (std::size_t i = 0; i < used.size(); ++i) {
    const compiler::ServoInfo* s = program.robot.find_id(used[i]);
    out +=
        fmt::format("{}\n    {{\"name\": {}, \"id\": {}, \"min\": {}, \"max\": {}, \"home\": {}}}",
                    i == 0 ? "" : ",", json_string(s->name), s->id, s->min, s->max, s->home);
  }
  out += "\n  ],\n  \"keyframes\": [";
  for (std::size_t i = 0; i < program.keyframes.size(); ++i) {
    const compiler::Keyframe& k = program.keyframes[i];
    out += fmt::format(
        "{}\n    {{\"start_ms\": {}, \"time_ms\": {}, \"source\": {}, \"targets\": [",
        i == 0 ? "" : ",", k.start_ms, k.time_ms, json_string(location_text(k.source, sources)));
    for (std::size_t j = 0; j < k.targets.size(); ++j) {
      const compiler::ServoInfo* s = program.robot.find_id(k.targets[j].id);
      out += fmt::format("{}{{\"servo\": {}, \"id\": {}, \"position\": {}}}", j == 0 ? "" : ", ",
                         json_string(s != nullptr ? s->name : ""), k.targets[j].id,
                         k.targets[j].position);
    }
    out += "]}";
  }
  out += "\n  ],\n  \"frames\": [";
  for (std::size_t i = 0; i < plan.size(); ++i) {
    out += fmt::format("{}\n    \"{}\"", i == 0 ? "" : ",", to_hex(plan[i].bytes));
  }
  out += "\n  ]\n}\n";
  return out;
}

}  // namespace seqc::compiler
