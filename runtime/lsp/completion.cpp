// textDocument/completion: what may be written at the cursor. Keys come from the tables the
// front end checks keys with (compiler/frontend/key_tables.hpp and the servo controllers' step
// table), chosen by where the cursor stands in the file's indentation, so a half-typed file
// still gets them; values are the file's poses and sections, the robot's servos and groups, the
// easings, the profiles and the time units.
#include <algorithm>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "compiler/frontend/key_tables.hpp"
#include "compiler/frontend/profiles.hpp"
#include "compiler/targets/servo_controller/servo_lowering.hpp"
#include "compiler/timeline/easing.hpp"
#include "runtime/lsp/feature_parts.hpp"

namespace seqc::lsp {

using nlohmann::json;

namespace {

// CompletionItemKind values of the protocol.
enum ItemKind : int {
  kFunction = 3,
  kVariable = 6,
  kModule = 9,
  kProperty = 10,
  kUnit = 11,
  kEnumMember = 20,
  kConstant = 21
};

struct Line {
  std::size_t indent = 0;   // spaces before the content (or the dash)
  bool dash = false;        // a list item: "- ..."
  std::size_t content = 0;  // where the content starts (after "- ")
  std::string key;          // "key" of "key: ..." / "key:", empty when none
  bool blank = true;
};

Line read_line(std::string_view text) {
  Line l;
  std::size_t i = 0;
  while (i < text.size() && text[i] == ' ') ++i;
  l.indent = i;
  if (i >= text.size() || text[i] == '#') return l;
  l.blank = false;
  if (text[i] == '-' && (i + 1 == text.size() || text[i + 1] == ' ')) {
    l.dash = true;
    i += 1;
    while (i < text.size() && text[i] == ' ') ++i;
  }
  l.content = i;
  const std::size_t colon = text.find(':', i);
  if (colon != std::string_view::npos && (colon + 1 == text.size() || text[colon + 1] == ' ')) {
    const std::string_view key = text.substr(i, colon - i);
    if (key.find_first_of("{[\"'") == std::string_view::npos) l.key = std::string(key);
  }
  return l;
}

struct Ancestor {
  std::string key;
  bool list = false;  // the child is an item of the list under this key
};

// The keys around the one at column `want` of line `row`, innermost first, and whether that key
// is in a list item.
std::vector<Ancestor> ancestors(const SourceManager& sources, std::uint32_t file, std::uint32_t row,
                                std::size_t want, bool item, bool& in_item) {
  std::vector<Ancestor> out;
  in_item = item;
  std::size_t dash_at = want;  // looking for a list's owner when `item`
  bool looking_for_owner = item;
  for (std::uint32_t r = row; r-- > 1;) {
    const Line l = read_line(sources.line(file, r));
    if (l.blank) continue;
    if (looking_for_owner) {
      if (l.dash && l.indent == dash_at) continue;  // an item before ours
      if (l.indent < dash_at || (l.indent == dash_at && !l.dash)) {
        if (l.key.empty()) break;
        out.push_back({l.key, true});
        looking_for_owner = l.dash;
        want = l.dash ? l.content : l.indent;
        dash_at = l.indent;
        if (l.dash) {
          // The owner is itself the first key of an item of an outer list.
          looking_for_owner = true;
        }
      }
      continue;
    }
    if (l.dash && l.content == want) {  // a key of the same item, above ours
      if (out.empty()) in_item = true;
      looking_for_owner = true;
      dash_at = l.indent;
      continue;
    }
    const std::size_t column = l.dash ? l.content : l.indent;
    if (column < want) {
      if (l.key.empty()) break;
      out.push_back({l.key, false});
      want = column;
      if (l.dash) {
        looking_for_owner = true;
        dash_at = l.indent;
      }
    }
  }
  return out;
}

void add_items(json& out, std::span<const std::string_view> labels, int kind,
               std::string_view suffix = {}) {
  for (std::string_view label : labels) {
    out.push_back({{"label", std::string(label)},
                   {"kind", kind},
                   {"insertText", std::string(label) + std::string(suffix)}});
  }
}

void add_names(json& out, const std::vector<std::string>& labels, int kind) {
  for (const std::string& label : labels) out.push_back({{"label", label}, {"kind", kind}});
}

std::vector<std::string> defined(const Analysis& a, NameKind kind) {
  std::vector<std::string> out;
  for (const Name& n : a.names()) {
    if (n.kind == kind && n.definition && std::find(out.begin(), out.end(), n.text) == out.end()) {
      out.push_back(n.text);
    }
  }
  return out;
}

void add_servos(json& out, const Analysis& a) {
  if (a.robot()) {
    std::vector<std::string> names;
    for (const auto& [name, index] : a.robot()->names) names.push_back(name);
    add_names(out, names, kVariable);
  }
  add_names(out, defined(a, NameKind::Group), kVariable);
}

void complete_value(json& out, const Analysis& a, const std::string& key, std::string_view word) {
  if (key == "move" || key == "pose") {
    std::vector<std::string> poses = defined(a, NameKind::Pose);
    if (std::find(poses.begin(), poses.end(), "home") == poses.end()) poses.push_back("home");
    add_names(out, poses, kConstant);
  } else if (key == "section") {
    add_names(out, defined(a, NameKind::Section), kFunction);
  } else if (key == "ease") {
    add_names(out, compiler::easing_names(), kEnumMember);
  } else if (key == "robot" || key == "profile") {
    add_names(out, compiler::profile_names(), kModule);
  } else if (key == "time" || key == "wait" || key == "at" || key == "downbeat") {
    std::string number;
    for (char c : word) {
      if ((c >= '0' && c <= '9') || c == '.' || c == '/') number += c;
    }
    for (const char* unit : {"ms", "s", "b", "bar"}) {
      out.push_back({{"label", number + unit}, {"kind", kUnit}});
    }
  }
}

// The files as `base` reads them, but the one at `path` with `text`: the document with the line
// being typed left out, so that the rest of a half-typed file still tells its names.
class WithText : public FileReader {
 public:
  WithText(FileReader& base, std::string path, std::string text)
      : base_(base), path_(std::move(path)), text_(std::move(text)) {}
  Result<std::string> read(const std::string& path) override {
    return path == path_ ? Result<std::string>(text_) : base_.read(path);
  }
  std::optional<std::uint64_t> size(const std::string& path) override {
    return path == path_ ? std::optional<std::uint64_t>(text_.size()) : base_.size(path);
  }

 private:
  FileReader& base_;
  std::string path_;
  std::string text_;
};

// The document without line `row` (1-based).
std::string without_line(const SourceManager& sources, std::uint32_t file, std::uint32_t row) {
  std::string out;
  for (std::uint32_t l = 1; l <= sources.line_count(file); ++l) {
    if (l != row) out += sources.line(file, l);
    out += '\n';
  }
  return out;
}

// The section the step holding line `row` performs: its `section:` on that line or on the
// lines of the step above it; empty when none.
std::string performed_section(const SourceManager& sources, std::uint32_t file, std::uint32_t row) {
  for (std::uint32_t r = row; r >= 1; --r) {
    const std::string_view text = sources.line(file, r);
    const Line l = read_line(text);
    const std::size_t at = text.find("section:");
    if (at != std::string_view::npos && (at == 0 || text[at - 1] == ' ' || text[at - 1] == '{')) {
      std::size_t from = at + 8;
      while (from < text.size() && text[from] == ' ') ++from;
      std::size_t to = from;
      while (to < text.size() && text[to] != ' ' && text[to] != ',' && text[to] != '}') ++to;
      return std::string(text.substr(from, to - from));
    }
    if (l.dash) break;  // the step's first line
  }
  return "";
}

std::vector<std::string> section_params(const Analysis& a, const std::string& section) {
  std::vector<std::string> out;
  for (const Name& n : a.names()) {
    if (n.kind == NameKind::Param && n.definition && n.section == section) out.push_back(n.text);
  }
  return out;
}

}  // namespace

json completion(Request& r) {
  json out = json::array();
  if (!r.position) return out;
  std::unique_ptr<Analysis> without;
  if (r.analysis->main_root() == nullptr) {
    WithText files(r.ctx.files, r.path,
                   without_line(r.analysis->sources(), *r.file, r.position->line + 1));
    without = Analysis::run(r.path, files, false);
  }
  // The names from the file without the line being typed when the whole did not parse; the
  // line itself from the document.
  const Analysis& a = without && without->main_root() ? *without : *r.analysis;
  const Analysis& doc = *r.analysis;
  const std::uint32_t row = r.position->line + 1;
  const std::string_view text = doc.sources().line(*r.file, row);
  const std::size_t cut =
      std::min<std::size_t>(doc.to_byte_column(*r.file, *r.position) - 1, text.size());
  const std::string_view prefix = text.substr(0, cut);
  // The word being typed.
  std::size_t word_start = prefix.size();
  while (word_start > 0 && prefix[word_start - 1] != ' ' && prefix[word_start - 1] != '{' &&
         prefix[word_start - 1] != ',' && prefix[word_start - 1] != ':') {
    --word_start;
  }
  const std::string_view word = prefix.substr(word_start);

  // Inside a flow map (`move: {cl`): servo names as keys (in `with:`, the section's
  // parameters), nothing as values.
  const std::size_t brace = prefix.rfind('{');
  if (brace != std::string_view::npos && prefix.find('}', brace) == std::string_view::npos) {
    const std::string_view inside = prefix.substr(brace + 1);
    const std::size_t comma = inside.rfind(',');
    const std::string_view entry = comma == std::string_view::npos ? inside : inside.substr(comma);
    if (entry.find(':') != std::string_view::npos) return out;
    std::string_view owner = prefix.substr(0, brace);
    while (!owner.empty() && owner.back() == ' ') owner.remove_suffix(1);
    if (owner.ends_with("with:")) {
      add_names(out, section_params(a, performed_section(doc.sources(), *r.file, row)), kVariable);
    } else {
      add_servos(out, a);
    }
    return out;
  }

  const Line line = read_line(prefix);
  if (!line.key.empty() || prefix.find(": ", line.content) != std::string_view::npos) {
    // A value: after "key: ".
    const std::size_t colon = prefix.find(':', line.content);
    const std::string key(prefix.substr(line.content, colon - line.content));
    complete_value(out, a, key, word);
    return out;
  }

  // A key.
  bool in_item = false;
  const std::size_t column = line.blank ? prefix.size() : line.content;
  const std::vector<Ancestor> up =
      ancestors(doc.sources(), *r.file, row, line.dash ? line.indent : column, line.dash, in_item);
  const compiler::StepTable& steps = compiler::servo_step_table();
  if (in_item) {
    const std::string owner = up.empty() ? "" : up[0].key;
    const std::string outer = up.size() > 1 ? up[1].key : "";
    if (owner == "through") {
      add_items(out, compiler::kWaypointKeys, kProperty, ": ");
    } else if (owner == "sequence" || owner == "steps" || owner == "do" || owner == "mirror" ||
               outer == "together" || outer == "sections") {
      add_items(out, steps.step_keys, kProperty, ": ");
    }
    return out;
  }
  if (up.empty()) {
    add_items(out, compiler::kServoFileKeys, kProperty, ": ");
    return out;
  }
  const std::string parent = up[0].key;
  const std::string grand = up.size() > 1 ? up[1].key : "";
  if (parent == "robot") {
    add_items(out, compiler::kRobotKeys, kProperty, ": ");
  } else if (parent == "music") {
    add_items(out, compiler::kMusicKeys, kProperty, ": ");
  } else if (grand == "servos") {
    add_items(out, compiler::kServoDefinitionKeys, kProperty, ": ");
  } else if (grand == "sections") {
    add_items(out, compiler::kSectionKeys, kProperty, ": ");
  } else if (parent == "move" || parent == "pose" || grand == "poses") {
    add_servos(out, a);
  } else if (parent == "with") {
    add_names(out, section_params(a, performed_section(doc.sources(), *r.file, row)), kVariable);
  }
  return out;
}

}  // namespace seqc::lsp
