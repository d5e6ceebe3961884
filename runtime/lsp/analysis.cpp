// Analysis (analysis.hpp): the file read once, walked once, and its names indexed.
#include "runtime/lsp/analysis.hpp"

#include <algorithm>

#include "compiler/frontend/reporter.hpp"
#include "compiler/program/program.hpp"
#include "compiler/targets/raspblock/raspblock_lowering.hpp"
#include "compiler/targets/servo_controller/servo_lowering.hpp"

namespace seqc::lsp {

using compiler::YamlNode;

namespace {

// The UTF-16 units a UTF-8 sequence starting with `lead` takes (a 4-byte one is a pair).
std::uint32_t utf16_units(unsigned char lead) { return lead >= 0xF0 ? 2 : 1; }
bool continuation(unsigned char c) { return (c & 0xC0) == 0x80; }

bool name_char(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
}

}  // namespace

std::optional<Span> scalar_span(const SourceManager& sources, const YamlNode& node) {
  if (!node.is_scalar() || node.scalar.empty() || node.location.line == 0) return std::nullopt;
  if (node.used_at.line != 0) return std::nullopt;  // a copy: its text is elsewhere
  if (node.location.file >= sources.file_count()) return std::nullopt;
  const std::string_view line = sources.line(node.location.file, node.location.line);
  std::size_t at = node.location.column - 1;
  if (at < line.size() && (line[at] == '"' || line[at] == '\'')) ++at;
  if (line.substr(std::min(at, line.size())).substr(0, node.scalar.size()) != node.scalar) {
    return std::nullopt;
  }
  return Span{node.location.file, node.location.line, static_cast<std::uint32_t>(at + 1),
              static_cast<std::uint32_t>(node.scalar.size())};
}

std::unique_ptr<Analysis> Analysis::run(const std::string& path, FileReader& files, bool walk) {
  std::unique_ptr<Analysis> a(new Analysis());
  a->loader_ = std::make_unique<compiler::FileLoader>(files, a->sources_, a->diags_);
  auto main = a->loader_->load(path);
  if (!main || !(*main)->root) {
    if (main) a->main_file_ = (*main)->file;
    return a;
  }
  const compiler::LoadedFile& file = **main;
  a->main_file_ = file.file;
  a->loaded_.push_back(&file);
  if (!file.root->is_map()) return a;
  a->load_includes(file, 0);

  // The robot and the walk, as the compiler's front end makes them (errors are the server's
  // diagnostics' business, not the features').
  compiler::Reporter reporter(a->diags_);
  reporter.set_alias_uses(&a->loader_->alias_uses());
  if (const YamlNode* r = file.root->find("robot")) a->robot_ = compiler::parse_robot(*r, reporter);
  if (walk && a->robot_ && a->robot_->info.kind == compiler::RobotKind::ServoController) {
    const std::size_t groups = compiler::stored_groups(a->robot_->profile);
    compiler::ServoWalk walked = compiler::walk_servo_file(
        *a->robot_, file, *a->loader_, reporter, std::max<std::size_t>(1, groups), {}, &a->times_);
    a->tempo_map_ = walked.timeline.tempo_map;
    if (walked.timeline.song) a->downbeat_ = walked.timeline.song->downbeat;
    a->walked_ = true;
  } else if (walk && a->robot_ && a->robot_->info.kind == compiler::RobotKind::Raspblock) {
    const compiler::RaspblockProgram car =
        compiler::lower_raspblock_program(*a->robot_, file, *a->loader_, reporter, &a->times_);
    a->tempo_map_ = car.timeline.tempo_map;
    if (car.timeline.song) a->downbeat_ = car.timeline.song->downbeat;
    a->walked_ = true;
  }

  for (const compiler::LoadedFile* f : a->loaded_) {
    const YamlNode* groups = f->root->find("groups");
    if (groups == nullptr || !groups->is_map()) continue;
    for (const auto& [key, value] : groups->entries) a->group_names_.push_back(key.scalar);
  }
  for (const compiler::LoadedFile* f : a->loaded_) a->index_file(*f);
  return a;
}

void Analysis::load_includes(const compiler::LoadedFile& f, std::size_t depth) {
  if (depth >= compiler::kMaxIncludeDepth || !f.root || !f.root->is_map()) return;
  // Every `include:` value anywhere in the file's steps and sections.
  std::vector<const YamlNode*> stack{f.root.operator->()};
  std::vector<std::string> targets;
  while (!stack.empty()) {
    const YamlNode* n = stack.back();
    stack.pop_back();
    for (const compiler::YamlEntry& e : n->entries) {
      if (e.first.scalar == "include" && e.second.is_scalar() && !e.second.scalar.empty()) {
        targets.push_back(compiler::resolve_include(f.path, e.second.scalar));
      }
      stack.push_back(&e.second);
    }
    for (const YamlNode& item : n->items) stack.push_back(&item);
  }
  for (const std::string& target : targets) {
    auto loaded = loader_->load_included(target);
    if (!loaded || !(*loaded)->root || !(*loaded)->root->is_map()) continue;
    if (std::find(loaded_.begin(), loaded_.end(), *loaded) != loaded_.end()) continue;
    loaded_.push_back(*loaded);
    load_includes(**loaded, depth + 1);
  }
}

const YamlNode* Analysis::main_root() const {
  if (loaded_.empty() || !loaded_.front()->root || !loaded_.front()->root->is_map()) return nullptr;
  return &*loaded_.front()->root;
}

void Analysis::add(NameKind kind, const YamlNode& node, std::uint32_t file, bool definition,
                   const std::string& section, const YamlNode* value) {
  const std::optional<Span> span = scalar_span(sources_, node);
  if (!span || span->file != file) return;
  Name n;
  n.kind = kind;
  n.text = node.scalar;
  n.span = *span;
  n.definition = definition;
  n.section = section;
  n.node = value;
  names_.push_back(std::move(n));
}

void Analysis::index_params_in(const YamlNode& node, std::uint32_t file,
                               const std::string& section) {
  if (section.empty()) return;
  if (node.is_scalar()) {
    const std::optional<Span> span = scalar_span(sources_, node);
    if (!span) return;
    const std::string& s = node.scalar;
    for (std::size_t i = 0; i < s.size(); ++i) {
      if (s[i] != '$') continue;
      const bool braced = i + 1 < s.size() && s[i + 1] == '{';
      const std::size_t from = i + (braced ? 2 : 1);
      std::size_t to = from;
      while (to < s.size() && name_char(s[to])) ++to;
      if (to == from) continue;
      Name n;
      n.kind = NameKind::Param;
      n.text = s.substr(from, to - from);
      n.span = Span{file, span->line, static_cast<std::uint32_t>(span->column + from),
                    static_cast<std::uint32_t>(to - from)};
      n.section = section;
      names_.push_back(std::move(n));
      i = to - 1;
    }
    return;
  }
  for (const compiler::YamlEntry& e : node.entries) {
    index_params_in(e.first, file, section);
    index_params_in(e.second, file, section);
  }
  for (const YamlNode& item : node.items) index_params_in(item, file, section);
}

void Analysis::index_positions(const YamlNode& map, std::uint32_t file,
                               const std::string& section) {
  if (!map.is_map()) return;
  for (const compiler::YamlEntry& e : map.entries) {
    const std::string& key = e.first.scalar;
    if (key.empty() || key[0] == '$') continue;
    if (key == "tip" || key == "pitch" || key == "elbow" || key == "<<") continue;
    const bool group =
        std::find(group_names_.begin(), group_names_.end(), key) != group_names_.end();
    add(group ? NameKind::Group : NameKind::Servo, e.first, file, false, section);
  }
}

void Analysis::index_steps(const YamlNode& list, std::uint32_t file, const std::string& section) {
  for (const YamlNode& step : list.items) index_step(step, file, section);
}

void Analysis::index_step(const YamlNode& step, std::uint32_t file, const std::string& section) {
  if (!step.is_map()) return;
  index_params_in(step, file, section);
  const YamlNode* performed = step.find("section");
  for (const compiler::YamlEntry& e : step.entries) {
    const std::string& key = e.first.scalar;
    const YamlNode& value = e.second;
    static constexpr std::string_view kVerbs[] = {"move",    "wait",   "through",  "repeat",
                                                  "include", "mirror", "section",  "together",
                                                  "tempo",   "meter",  "tolerance"};
    if (std::find(std::begin(kVerbs), std::end(kVerbs), key) != std::end(kVerbs)) {
      add(NameKind::Step, e.first, file, false, section, &step);
    }
    if (key == "move") {
      if (value.is_scalar() && !value.scalar.empty() && value.scalar[0] != '$') {
        add(NameKind::Pose, value, file, false, section);
      }
      index_positions(value, file, section);
    } else if (key == "through" && value.is_sequence()) {
      for (const YamlNode& wp : value.items) {
        const YamlNode* pose = wp.is_map() ? wp.find("pose") : nullptr;
        if (pose == nullptr) continue;
        if (pose->is_scalar() && !pose->scalar.empty() && pose->scalar[0] != '$') {
          add(NameKind::Pose, *pose, file, false, section);
        }
        index_positions(*pose, file, section);
      }
    } else if (key == "section" && value.is_scalar()) {
      add(NameKind::Section, value, file, false, section);
    } else if (key == "with" && value.is_map() && performed && performed->is_scalar()) {
      for (const compiler::YamlEntry& w : value.entries) {
        add(NameKind::Param, w.first, file, false, performed->scalar);
      }
    } else if (key == "include" && value.is_scalar()) {
      const std::size_t before = names_.size();
      add(NameKind::Include, value, file, false, section, &value);
      if (names_.size() > before) {
        names_.back().target = compiler::resolve_include(sources_.path(file), value.scalar);
      }
    } else if (key == "ease" && value.is_scalar()) {
      add(NameKind::Easing, value, file, false, section);
    } else if ((key == "do" || key == "mirror") && value.is_sequence()) {
      index_steps(value, file, section);
    } else if (key == "together" && value.is_map()) {
      for (const compiler::YamlEntry& track : value.entries) {
        if (track.second.is_sequence()) index_steps(track.second, file, section);
      }
    }
  }
}

void Analysis::index_file(const compiler::LoadedFile& f) {
  const YamlNode& root = *f.root;
  const std::uint32_t file = f.file;
  if (const YamlNode* robot = root.find("robot"); robot && robot->is_map()) {
    if (const YamlNode* servos = robot->find("servos"); servos && servos->is_map()) {
      for (const compiler::YamlEntry& e : servos->entries) {
        add(NameKind::Servo, e.first, file, true, {}, &e.second);
      }
    }
  }
  if (const YamlNode* groups = root.find("groups"); groups && groups->is_map()) {
    for (const compiler::YamlEntry& e : groups->entries) {
      add(NameKind::Group, e.first, file, true, {}, &e.second);
      for (const YamlNode& member : e.second.items) add(NameKind::Servo, member, file, false);
    }
  }
  if (const YamlNode* poses = root.find("poses"); poses && poses->is_map()) {
    for (const compiler::YamlEntry& e : poses->entries) {
      add(NameKind::Pose, e.first, file, true, {}, &e.second);
      index_positions(e.second, file, {});
    }
  }
  if (const YamlNode* sections = root.find("sections"); sections && sections->is_map()) {
    for (const compiler::YamlEntry& e : sections->entries) {
      const std::string& name = e.first.scalar;
      add(NameKind::Section, e.first, file, true, {}, &e.second);
      const YamlNode* steps = &e.second;
      if (e.second.is_map()) {
        if (const YamlNode* params = e.second.find("params"); params && params->is_map()) {
          for (const compiler::YamlEntry& p : params->entries) {
            add(NameKind::Param, p.first, file, true, name, &p.second);
          }
        }
        steps = e.second.find("steps");
      }
      if (steps != nullptr && steps->is_sequence()) index_steps(*steps, file, name);
    }
  }
  if (const YamlNode* sequence = root.find("sequence"); sequence && sequence->is_sequence()) {
    index_steps(*sequence, file, {});
  }
}

const Name* Analysis::name_at(std::uint32_t file, TextPos pos) const {
  const std::uint32_t line = pos.line + 1;
  const std::uint32_t column = to_byte_column(file, pos);
  const Name* best = nullptr;
  for (const Name& n : names_) {
    if (n.span.file != file || n.span.line != line) continue;
    if (column < n.span.column || column > n.span.column + n.span.length) continue;
    // A parameter inside a value is a narrower match than the value itself.
    if (best == nullptr || n.span.length < best->span.length) best = &n;
  }
  return best;
}

std::vector<const Name*> Analysis::same(const Name& name) const {
  std::vector<const Name*> out;
  for (const Name& n : names_) {
    if (n.kind != name.kind || n.text != name.text) continue;
    if (n.kind == NameKind::Param && n.section != name.section) continue;
    if (n.kind == NameKind::Include && n.target != name.target) continue;
    out.push_back(&n);
  }
  return out;
}

const Name* Analysis::definition_of(const Name& name) const {
  if (name.definition) return &name;
  const Name* found = nullptr;
  for (const Name* n : same(name)) {
    if (!n->definition) continue;
    // The definition in the name's own file first, as the compiler looks names up.
    if (n->span.file == name.span.file) return n;
    if (found == nullptr) found = n;
  }
  return found;
}

std::optional<std::uint32_t> Analysis::file_of(std::string_view path) const {
  for (std::uint32_t f = 0; f < sources_.file_count(); ++f) {
    if (sources_.path(f) == path) return f;
  }
  return std::nullopt;
}

TextPos Analysis::to_protocol(std::uint32_t file, std::uint32_t line, std::uint32_t column) const {
  const std::string_view text = file < sources_.file_count() ? sources_.line(file, line) : "";
  std::uint32_t units = 0;
  for (std::size_t i = 0; i + 1 < column && i < text.size(); ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (!continuation(c)) units += utf16_units(c);
  }
  return TextPos{line == 0 ? 0 : line - 1, units};
}

std::uint32_t Analysis::to_byte_column(std::uint32_t file, TextPos pos) const {
  const std::string_view text =
      file < sources_.file_count() ? sources_.line(file, pos.line + 1) : "";
  std::uint32_t units = 0;
  std::size_t i = 0;
  while (i < text.size() && units < pos.character) {
    units += utf16_units(static_cast<unsigned char>(text[i]));
    ++i;
    while (i < text.size() && continuation(static_cast<unsigned char>(text[i]))) ++i;
  }
  return static_cast<std::uint32_t>(i + 1);
}

std::uint32_t Analysis::line_end_column(std::uint32_t file, std::uint32_t line) const {
  const std::string_view text = file < sources_.file_count() ? sources_.line(file, line) : "";
  return static_cast<std::uint32_t>(text.size() + 1);
}

}  // namespace seqc::lsp
