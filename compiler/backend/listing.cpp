#include "compiler/backend/listing.hpp"
#include "compiler/source/json_text.hpp"

#include <fmt/format.h>

#include "compiler/source/units.hpp"

namespace seqc::backend {
using compiler::json_string;
namespace {

std::string servo_label(const compiler::ServoProgram& program, std::uint8_t id) {
  const compiler::ServoInfo* s = program.robot.find_id(id);
  return s != nullptr ? fmt::format("{}({})", s->name, id) : fmt::format("servo({})", id);
}

std::string join_counts(const std::vector<std::uint8_t>& counts) {
  std::string s;
  for (std::uint8_t c : counts) s += (s.empty() ? "" : " ") + std::to_string(c);
  return s;
}

// The labelled fields of a GroupDownload step (the only requests a download plan holds).
struct FieldsOf {
  std::string operator()(const lsc::GroupDownloadOpen& m) const {
    return fmt::format("step 1 open | group {} | block counts {}", m.group,
                       join_counts(m.block_counts));
  }
  std::string operator()(const lsc::GroupDownloadSize& m) const {
    return fmt::format("step 2 size | group {} | block {} | count {} | pad 00", m.group, m.block,
                       m.count);
  }
  std::string operator()(const lsc::GroupDownloadBlocks& m) const {
    return fmt::format("step 3 blocks | group {} | pad 00 | blocks used {}", m.group,
                       m.block_count);
  }
  std::string operator()(const lsc::GroupDownloadAction& m) const {
    return fmt::format(
        "step 4 action | group {} | block {} | index {} | marker 0b | time {} ms | servos {}",
        m.group, m.block, m.index, m.time_ms, m.servos.size());
  }
  std::string operator()(const lsc::GroupDownloadClose& m) const {
    return fmt::format("step 5 close | group {}", m.group);
  }
  template <class Other>
  std::string operator()(const Other& other) const {
    return lsc::describe(lsc::Request{other});
  }
};

std::string fields(const DialectRequest& request) {
  if (const auto* lsc6_request = std::get_if<lsc6::Request>(&request)) {
    if (const auto* a = std::get_if<lsc6::DownloadAction>(lsc6_request)) {
      return fmt::format(
          "download action | group {} | total {} | index {} | time {} ms | servos {}", a->group,
          a->total, a->index, a->time_ms, a->servos.size());
    }
    return lsc6::describe(*lsc6_request);
  }
  return std::visit(FieldsOf{}, std::get<lsc::Request>(request));
}

}  // namespace

std::string location_text(const compiler::Location& at, const compiler::SourceManager& sources) {
  if (at.line == 0 || at.file >= sources.file_count()) return "";
  return fmt::format("{}:{}:{}", sources.path(at.file), at.line, at.column);
}

std::string render_hex(const std::vector<PlannedFrame>& plan) {
  std::string out;
  for (const PlannedFrame& p : plan) out += to_hex(p.serial) + "\n";
  return out;
}

std::string render_listing(const compiler::ServoProgram& program,
                           const std::vector<PlannedFrame>& plan, std::uint8_t group,
                           const compiler::SourceManager& sources) {
  const std::size_t n = program.keyframes.size();
  const std::size_t blocks = (n + lsc::kActionsPerBlock - 1) / lsc::kActionsPerBlock;
  const std::string storage = uses_lsc6_dialect(program)
                                  ? std::string(" (LSC-6 dialect)")
                                  : fmt::format(" in {} block{}", blocks, blocks == 1 ? "" : "s");
  std::string out = fmt::format("# robot {}, group {}: {} action{}{}, {} frames, {}\n",
                                program.robot.profile, group, n, n == 1 ? "" : "s", storage,
                                plan.size(), compiler::format_seconds(program.duration_ms()));
  for (std::size_t i = 0; i < plan.size(); ++i) {
    const PlannedFrame& p = plan[i];
    out += fmt::format("frame {}: {}\n", i + 1, to_hex(p.serial));
    out += fmt::format("  header 55 55 | len {} | cmd {:02x} | {}\n", p.serial.size() - 2,
                       p.frame.cmd, fields(p.request));
    if (!p.keyframe) continue;
    const compiler::Keyframe& k = program.keyframes[*p.keyframe];
    out += fmt::format("  action {} at {} ms from {}:", *p.keyframe + 1, k.start_ms,
                       location_text(k.source, sources));
    for (const lsc::ServoTarget& t : k.targets) {
      out += fmt::format(" {}={}", servo_label(program, t.id), t.position);
    }
    out += "\n";
  }
  return out;
}

std::string render_json(const compiler::ServoProgram& program,
                        const std::vector<PlannedFrame>& plan, std::uint8_t group,
                        const compiler::SourceManager& sources) {
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
    out += fmt::format("{}\n    \"{}\"", i == 0 ? "" : ",", to_hex(plan[i].serial));
  }
  out += "\n  ]\n}\n";
  return out;
}

}  // namespace seqc::backend
