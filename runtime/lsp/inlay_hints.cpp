// textDocument/inlayHint: at the end of each step's first line, when the step starts in the song
// (seconds, bar:beat) and how long it lasts; for a block (a section's performance, a repeat, an
// include, a together) its span from start to end. Only the steps of the requested range.
#include <cstdint>
#include <string>
#include <utility>

#include "runtime/lsp/feature_parts.hpp"

namespace seqc::lsp {

using nlohmann::json;

namespace {

bool is_block(const compiler::YamlNode& step) {
  return step.find("section") || step.find("repeat") || step.find("include") ||
         step.find("together") || step.find("mirror");
}

// The requested range's lines, [first, last], 0-based; everything when absent.
std::pair<std::uint32_t, std::uint32_t> requested_lines(const json& params) {
  std::pair<std::uint32_t, std::uint32_t> lines{0, UINT32_MAX};
  const auto range = params.find("range");
  if (range == params.end() || !range->is_object()) return lines;
  const std::optional<TextPos> start = protocol_position(range->value("start", json()));
  const std::optional<TextPos> end = protocol_position(range->value("end", json()));
  if (start) lines.first = start->line;
  if (end) lines.second = end->line;
  return lines;
}

}  // namespace

std::string step_hint_text(const Analysis& a, const compiler::YamlNode& step,
                           const compiler::StepTime& t) {
  const compiler::TempoMap& map = a.tempo_map();
  std::string text = instant_text(map, t.start);
  if (is_block(step)) {
    text += " \u2013 " + instant_text(map, t.end);
  } else if (t.end > t.start) {
    text += " \u00B7 " + duration_text(t.end - t.start);
  }
  if (t.performances > 1) text += " \u00B7 \u00D7" + std::to_string(t.performances);
  return text;
}

json inlay_hints(Request& r) {
  json out = json::array();
  const Analysis& a = *r.analysis;
  if (!a.walked()) return out;
  const auto [first, last] = requested_lines(r.params);
  std::uint32_t previous_line = 0;
  for (const Name& n : a.names()) {
    if (n.kind != NameKind::Step || n.span.file != *r.file || n.node == nullptr) continue;
    const compiler::YamlNode& step = *n.node;
    const compiler::StepTime* t = a.times().find(step.location);
    if (t == nullptr) continue;
    const std::uint32_t line = step.location.line;  // 1-based
    if (line == 0 || line - 1 < first || line - 1 > last) continue;
    // One hint for a step that gives two verbs (a mistake the diagnostics name).
    if (line == previous_line) continue;
    previous_line = line;
    const TextPos at = a.to_protocol(*r.file, line, a.line_end_column(*r.file, line));
    out.push_back({{"position", position_json(at)},
                   {"label", step_hint_text(a, step, *t)},
                   {"paddingLeft", true}});
  }
  return out;
}

}  // namespace seqc::lsp
