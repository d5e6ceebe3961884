// The features' entry point (features.hpp): what the server announces, and each request sent to
// the feature that answers it, with the document read and analysed once per request.
#include "runtime/lsp/features.hpp"

#include <cmath>
#include <cstdio>

#include "runtime/lsp/feature_parts.hpp"

namespace seqc::lsp {

using nlohmann::json;

nlohmann::json feature_capabilities() {
  return {
      {"inlayHintProvider", true},
      {"hoverProvider", true},
      {"definitionProvider", true},
      {"referencesProvider", true},
      {"renameProvider", {{"prepareProvider", true}}},
      {"completionProvider", {{"triggerCharacters", {":", " ", "{", "$"}}}},
      {"codeActionProvider", {{"codeActionKinds", {"quickfix"}}}},
      {"documentSymbolProvider", true},
  };
}

Request read_request(const json& params, FeatureContext& ctx, bool walk) {
  Request r{ctx, params, {}, {}, nullptr, std::nullopt, std::nullopt};
  if (!params.is_object()) return r;
  const auto doc = params.find("textDocument");
  if (doc == params.end() || !doc->is_object() || !doc->contains("uri") ||
      !(*doc)["uri"].is_string()) {
    return r;
  }
  r.uri = (*doc)["uri"].get<std::string>();
  r.path = ctx.uri_to_path(r.uri);
  if (const auto pos = params.find("position"); pos != params.end()) {
    r.position = protocol_position(*pos);
  }
  if (r.path.empty()) return r;
  r.analysis = Analysis::run(r.path, ctx.files, walk);
  r.file = r.analysis->main_file();
  // A position past the end of the document asks about nothing.
  if (r.file && r.position && r.position->line >= r.analysis->sources().line_count(*r.file)) {
    r.position.reset();
  }
  return r;
}

std::optional<std::uint32_t> protocol_number(const json& v) {
  if (!v.is_number_integer()) return std::nullopt;
  const std::int64_t n = v.get<std::int64_t>();
  if (n < 0 || n > std::int64_t{UINT32_MAX}) return std::nullopt;
  return static_cast<std::uint32_t>(n);
}

std::optional<TextPos> protocol_position(const json& v) {
  if (!v.is_object()) return std::nullopt;
  const std::optional<std::uint32_t> line = protocol_number(v.value("line", json()));
  const std::optional<std::uint32_t> character = protocol_number(v.value("character", json()));
  if (!line || !character) return std::nullopt;
  return TextPos{*line, *character};
}

json position_json(TextPos p) { return {{"line", p.line}, {"character", p.character}}; }

json range_json(const Analysis& a, const Span& s) {
  return {{"start", position_json(a.to_protocol(s.file, s.line, s.column))},
          {"end", position_json(a.to_protocol(s.file, s.line, s.column + s.length))}};
}

std::string uri_of(const Request& r, std::uint32_t file) {
  return r.ctx.path_to_uri(r.analysis->sources().path(file));
}

json location_json(const Request& r, const Span& s) {
  return {{"uri", uri_of(r, s.file)}, {"range", range_json(*r.analysis, s)}};
}

std::string seconds_text(compiler::ExactMs t) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.3f s", t.value() / 1000.0);
  return buf;
}

namespace {

// A count of beats with at most three decimals and no trailing zeros: "3", "2.5".
std::string beats_number(double beats) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.3f", beats);
  std::string s = buf;
  while (!s.empty() && s.back() == '0') s.pop_back();
  if (!s.empty() && s.back() == '.') s.pop_back();
  return s;
}

}  // namespace

std::string bar_beat_text(const compiler::TempoMap& map, compiler::ExactMs t) {
  if (map.bpm_at(t) <= 0) return "";
  const compiler::ExactMs beat = map.beat_at(t);
  if (map.meter_at(t) <= 0) return "beat " + beats_number(beat.value() + 1);
  const compiler::ExactMs bars = map.bar_of_beat(beat);
  const std::int64_t bar = bars.den() == 0 ? 0 : bars.num() / bars.den();
  const std::optional<compiler::ExactMs> bar_start = map.beat_of_bar(compiler::ExactMs(bar));
  if (!bar_start) return "beat " + beats_number(beat.value() + 1);
  return std::to_string(bar + 1) + ":" + beats_number((beat - *bar_start).value() + 1);
}

std::string instant_text(const compiler::TempoMap& map, compiler::ExactMs t) {
  const std::string bar_beat = bar_beat_text(map, t);
  return seconds_text(t) + (bar_beat.empty() ? "" : " \u00B7 " + bar_beat);
}

std::string duration_text(compiler::ExactMs d) {
  const double ms = d.value();
  char buf[48];
  if (ms < 1000) {
    if (ms == std::floor(ms)) {
      std::snprintf(buf, sizeof buf, "%.0f ms", ms);
    } else {
      std::snprintf(buf, sizeof buf, "%.3f ms", ms);
    }
  } else {
    std::snprintf(buf, sizeof buf, "%.3f s", ms / 1000.0);
  }
  return buf;
}

std::optional<json> answer_feature(std::string_view method, const json& params,
                                   FeatureContext& ctx) {
  using Answer = json (*)(Request&);
  struct Route {
    std::string_view method;
    Answer answer;
    json empty;  // the answer for a document that cannot be read
    bool walk;   // whether it shows when steps run
  };
  static const Route kRoutes[] = {
      {"textDocument/inlayHint", inlay_hints, json::array(), true},
      {"textDocument/hover", hover, nullptr, true},
      {"textDocument/definition", definition, nullptr, false},
      {"textDocument/references", references, json::array(), false},
      {"textDocument/prepareRename", prepare_rename, nullptr, false},
      {"textDocument/rename", rename, nullptr, false},
      {"textDocument/completion", completion, json::array(), false},
      {"textDocument/codeAction", code_actions, json::array(), false},
      {"textDocument/documentSymbol", document_symbols, json::array(), false},
  };
  for (const Route& route : kRoutes) {
    if (route.method != method) continue;
    Request r = read_request(params, ctx, route.walk);
    if (!r.file) return route.empty;
    return route.answer(r);
  }
  return std::nullopt;
}

}  // namespace seqc::lsp
