#include "compiler/frontend/reporter.hpp"

#include <fmt/format.h>

#include <iterator>

namespace seqc::compiler {

void Reporter::report(Severity severity, Location at, std::string message,
                      std::vector<Note> notes) {
  // Something with no place in any file (the built-in `home` pose) is wrong where it is used.
  if (at.line == 0 && !notes.empty() && notes.front().at.line > 0) {
    at = notes.front().at;
    notes.erase(notes.begin());
  }
  auto key = std::make_tuple(static_cast<int>(severity), at.file, at.line, at.column, message);
  if (!seen_.insert(std::move(key)).second) return;
  if (severity == Severity::Error) {
    ++errors_;
    diags_.error(at, std::move(message));
  } else if (severity == Severity::Warning) {
    diags_.warning(at, std::move(message));
  } else {
    diags_.note(at, std::move(message));
  }
  note_alias_uses(at);
  for (Note& n : notes) diags_.note(n.at, std::move(n.message));
  for (auto it = performing_.rbegin(); it != performing_.rend(); ++it) {
    if (it->with_values) diags_.note(it->note.at, it->note.message);
  }
  if (severity == Severity::Warning) {
    for (auto it = performing_.rbegin(); it != performing_.rend(); ++it) {
      if (!it->with_values && !it->pass) diags_.note(it->note.at, it->note.message);
    }
  }
  for (auto it = includes_.rbegin(); it != includes_.rend(); ++it) {
    diags_.note(*it, "included from here");
  }
}

std::vector<Reporter::Note> Reporter::chain() const {
  std::vector<Note> notes;
  for (auto it = performing_.rbegin(); it != performing_.rend(); ++it) notes.push_back(it->note);
  for (auto it = includes_.rbegin(); it != includes_.rend(); ++it) {
    notes.push_back({*it, "included from here"});
  }
  return notes;
}

void Reporter::error_with_notes(Location at, std::string message, const std::vector<Note>& notes) {
  auto key =
      std::make_tuple(static_cast<int>(Severity::Error), at.file, at.line, at.column, message);
  if (!seen_.insert(std::move(key)).second) return;
  ++errors_;
  diags_.error(at, std::move(message));
  note_alias_uses(at);
  for (const Note& n : notes) diags_.note(n.at, n.message);
}

// A mistake said at an anchored node (or inside it) was copied to each alias: say where.
void Reporter::note_alias_uses(Location at) {
  if (alias_uses_ == nullptr) return;
  for (const Location& site : alias_uses_->sites(at)) diags_.note(site, "used here");
}

void Reporter::unknown(Location at, std::string_view what, std::string_view word,
                       const std::vector<std::string>& candidates, std::string_view where,
                       std::string_view known) {
  std::string message = fmt::format("unknown {} '{}'", what, word);
  if (!where.empty()) fmt::format_to(std::back_inserter(message), " {}", where);
  const std::string suggestion = did_you_mean(word, candidates);
  if (!suggestion.empty()) message += "; did you mean '" + suggestion + "'?";
  if (!known.empty()) fmt::format_to(std::back_inserter(message), " ({})", known);
  error(at, std::move(message));
}

void Reporter::check_free_text(const YamlNode& root) {
  for (const char* key : {"name", "description"}) {
    const YamlNode* node = root.find(key);
    if (node != nullptr && !node->is_scalar() && node->kind != YamlNode::Kind::Null) {
      error(node->location, fmt::format("'{}' is free text, not {}", key, kind_name(*node)));
    }
  }
}

bool Reporter::check_keys(const YamlNode& map, std::span<const std::string_view> allowed,
                          std::string_view where) {
  bool ok = true;
  for (const auto& [key, value] : map.entries) {
    bool known = false;
    for (std::string_view a : allowed) known = known || key.scalar == a;
    if (!known) {
      // Built only for a mistake: this runs for every step of every file.
      const std::vector<std::string> candidates(allowed.begin(), allowed.end());
      unknown(key.location, "key", key.scalar, candidates, where);
      ok = false;
    }
  }
  return ok;
}

}  // namespace seqc::compiler
