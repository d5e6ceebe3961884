// textDocument/codeAction: quick fixes the compiler's own messages spell out. A diagnostic that
// ends "did you mean 'time'?" replaces the word it quotes first ('tme') with the suggestion; one
// that says "write '500ms' or '500s'" offers each. The word is looked for on the diagnostic's
// line from where its range starts, so a fix never edits anything but that word.
#include <string>
#include <vector>

#include "runtime/lsp/feature_parts.hpp"

namespace seqc::lsp {

using nlohmann::json;

namespace {

// The words a message quotes in single quotes, in order.
std::vector<std::string> quoted_words(const std::string& message) {
  std::vector<std::string> out;
  std::size_t at = 0;
  while (true) {
    const std::size_t open = message.find('\'', at);
    if (open == std::string::npos) break;
    const std::size_t close = message.find('\'', open + 1);
    if (close == std::string::npos) break;
    out.push_back(message.substr(open + 1, close - open - 1));
    at = close + 1;
  }
  return out;
}

// What a message suggests: the replacements, and the part of the message before them, which
// quotes the word to replace.
struct Suggestion {
  std::vector<std::string> fixes;
  std::string before;
};

Suggestion suggestions(const std::string& message) {
  Suggestion out;
  const std::size_t mean = message.rfind("did you mean '");
  if (mean != std::string::npos) {
    const std::size_t from = mean + 14;
    const std::size_t to = message.find('\'', from);
    if (to != std::string::npos) out.fixes.push_back(message.substr(from, to - from));
    out.before = message.substr(0, mean);
    return out;
  }
  const std::size_t write = message.rfind("; write '");
  if (write != std::string::npos) {
    out.fixes = quoted_words(message.substr(write));
    out.before = message.substr(0, write);
  }
  return out;
}

}  // namespace

json code_actions(Request& r) {
  json out = json::array();
  const Analysis& a = *r.analysis;
  const json context = r.params.value("context", json::object());
  const json diagnostics =
      context.is_object() ? context.value("diagnostics", json::array()) : json::array();
  if (!diagnostics.is_array()) return out;
  for (const json& d : diagnostics) {
    if (!d.is_object() || !d.value("message", json()).is_string()) continue;
    const std::string message = d["message"].get<std::string>();
    const Suggestion suggestion = suggestions(message);
    if (suggestion.fixes.empty()) continue;
    const json range = d.value("range", json::object());
    const std::optional<TextPos> start =
        range.is_object() ? protocol_position(range.value("start", json())) : std::nullopt;
    if (!start || start->line >= a.sources().line_count(*r.file)) continue;
    const std::string_view line = a.sources().line(*r.file, start->line + 1);
    const std::size_t from = a.to_byte_column(*r.file, *start) - 1;
    // The quoted word written where the diagnostic starts ('amout' of "section 'nod' has no
    // parameter 'amout'"), else the first one written after it on its line.
    std::string word;
    std::size_t at = std::string_view::npos;
    for (const std::string& w : quoted_words(suggestion.before)) {
      if (w.empty()) continue;
      if (line.substr(std::min(from, line.size())).starts_with(w)) {
        word = w;
        at = from;
        break;
      }
      const std::size_t found = line.find(w, from);
      if (found != std::string_view::npos && (at == std::string_view::npos || found < at)) {
        word = w;
        at = found;
      }
    }
    if (at == std::string_view::npos) continue;
    const std::vector<std::string>& fixes = suggestion.fixes;
    const Span span{*r.file, start->line + 1, static_cast<std::uint32_t>(at + 1),
                    static_cast<std::uint32_t>(word.size())};
    for (std::size_t i = 0; i < fixes.size(); ++i) {
      if (fixes[i] == word) continue;
      json edit = {{"range", range_json(a, span)}, {"newText", fixes[i]}};
      out.push_back({{"title", "Change '" + word + "' to '" + fixes[i] + "'"},
                     {"kind", "quickfix"},
                     {"diagnostics", json::array({d})},
                     {"isPreferred", i == 0},
                     {"edit", {{"changes", {{r.uri, json::array({edit})}}}}}});
    }
  }
  return out;
}

}  // namespace seqc::lsp
