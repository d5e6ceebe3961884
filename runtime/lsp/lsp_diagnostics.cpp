#include "runtime/lsp/lsp_diagnostics.hpp"

#include <string_view>

#include "base/diagnostic_rules.hpp"
#include "runtime/lsp/documents.hpp"

namespace seqc::lsp {
namespace {

using nlohmann::json;

json position(std::uint32_t line, std::uint32_t character) {
  return {{"line", line}, {"character", character}};
}

// Bytes of the token that starts at `from` in `line`: a quoted string with its quotes, or a
// run of characters up to a space or YAML punctuation.
std::size_t token_bytes(std::string_view line, std::size_t from) {
  if (from >= line.size()) return 0;
  const char first = line[from];
  if (first == '"' || first == '\'') {
    const std::size_t close = line.find(first, from + 1);
    return close == std::string_view::npos ? line.size() - from : close + 1 - from;
  }
  std::size_t i = from;
  while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r' &&
         line[i] != ':' && line[i] != ',' && line[i] != '[' && line[i] != ']' && line[i] != '{' &&
         line[i] != '}' && line[i] != '#') {
    ++i;
  }
  return i - from;
}

struct Where {
  std::string path;  // normal
  json range;
};

Where where(const SourceManager& sources, const Location& at, const std::string& main_path) {
  if (at.file >= sources.file_count()) return {normal_path(main_path), lsp_range(sources, at)};
  return {normal_path(sources.path(at.file)), lsp_range(sources, at)};
}

}  // namespace

json lsp_range(const SourceManager& sources, const Location& at) {
  if (at.file >= sources.file_count() || at.line == 0) {
    return {{"start", position(0, 0)}, {"end", position(0, 0)}};
  }
  const std::string_view line = sources.line(at.file, at.line);
  const std::size_t from = std::min<std::size_t>(at.column == 0 ? 0 : at.column - 1, line.size());
  const std::uint32_t start = utf16_length(line.substr(0, from));
  const std::uint32_t width = utf16_length(line.substr(from, token_bytes(line, from)));
  return {{"start", position(at.line - 1, start)}, {"end", position(at.line - 1, start + width)}};
}

void add_lsp_diagnostics(const SourceManager& sources, const Diagnostics& diagnostics,
                         const std::string& main_path, const std::optional<std::string>& read_error,
                         FileDiagnostics& into) {
  if (read_error) {
    json& list = into[normal_path(main_path)];
    if (!list.is_array()) list = json::array();
    list.push_back({{"range", lsp_range(sources, {kNoFile, 0, 0})},
                    {"severity", 1},
                    {"code", "file-error"},
                    {"source", "seqc"},
                    {"message", *read_error}});
    return;
  }
  json* last = nullptr;  // the diagnostic the next notes belong to
  for (const Diagnostic& d : diagnostics.all()) {
    const Where at = where(sources, d.location, main_path);
    if (d.severity == Severity::Note) {
      if (last == nullptr) continue;
      (*last)["relatedInformation"].push_back(
          {{"location", {{"uri", path_to_uri(at.path)}, {"range", at.range}}},
           {"message", d.message}});
      continue;
    }
    json& list = into[at.path];
    if (!list.is_array()) list = json::array();
    list.push_back({{"range", at.range},
                    {"severity", d.severity == Severity::Error ? 1 : 2},
                    {"code", std::string(rule_for(d).id)},
                    {"source", "seqc"},
                    {"message", d.message}});
    last = &list.back();
  }
}

}  // namespace seqc::lsp
