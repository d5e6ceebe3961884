#include "compiler/frontend/scope_chain.hpp"

#include <cmath>
#include <cstdint>
#include <string_view>

#include "base/units.hpp"
#include "compiler/frontend/music_section.hpp"
#include "compiler/frontend/robot_section.hpp"

namespace seqc::compiler {
namespace {

// What a broken `music:` block's unreadable tempo or meter counts as while the steps are checked:
// any value would do, as the file already has an error and makes no program.
constexpr Tempo kStandInTempo{120, 0, 0};
constexpr TimeSignature kStandInMeter{4, 4};

// A note name of a tempo, as a fraction of a whole note.
struct NoteName {
  std::string_view name;
  std::int64_t den;
};
constexpr NoteName kNoteNames[] = {
    {"whole", 1}, {"half", 2}, {"quarter", 4}, {"eighth", 8}, {"sixteenth", 16}};

// "3/8", "quarter", "dotted quarter" as num/den of a whole note; false for anything else.
bool parse_tempo_note(std::string_view text, std::int64_t& num, std::int64_t& den) {
  const auto trim = [](std::string_view t) {
    while (!t.empty() && t.front() == ' ') t.remove_prefix(1);
    while (!t.empty() && t.back() == ' ') t.remove_suffix(1);
    return t;
  };
  text = trim(text);
  const std::size_t slash = text.find('/');
  if (slash != std::string_view::npos) {
    double n = 0, d = 0;
    if (!parse_decimal(text.substr(0, slash), n) || !parse_decimal(text.substr(slash + 1), d) ||
        n != std::floor(n) || n < 1 || n > 32 ||
        (d != 1 && d != 2 && d != 4 && d != 8 && d != 16 && d != 32)) {
      return false;
    }
    num = static_cast<std::int64_t>(n);
    den = static_cast<std::int64_t>(d);
    return true;
  }
  bool dotted = false;
  if (text.substr(0, 7) == "dotted ") {
    dotted = true;
    text = trim(text.substr(7));
  }
  for (const NoteName& note : kNoteNames) {
    if (text != note.name) continue;
    num = dotted ? 3 : 1;
    den = dotted ? note.den * 2 : note.den;
    return true;
  }
  return false;
}

}  // namespace

std::pair<FileScope&, bool> ScopeChain::open(const LoadedFile& f, Reporter& reporter) {
  auto it = scopes_.find(f.path);
  if (it != scopes_.end()) return {*it->second, false};
  auto scope = std::make_unique<FileScope>();
  scope->file = &f;
  const YamlEntry* music = nullptr;
  for (const YamlEntry& e : f.root->entries) {
    if (e.first.scalar == "music") music = &e;
  }
  if (music != nullptr) {
    // The song owns the one tempo map: a tempo or meter beside it would be a second one.
    scope->song = parse_music(music->first, music->second, f.path, reporter);
    scope->song_file = music_file(music->second, f.path);
    for (std::string_view key : {"tempo", "meter"}) {
      if (const YamlNode* v = f.root->find(key)) {
        reporter.error(v->location,
                       "'" + std::string(key) + "' beside 'music': the song sets the " +
                           (key == "tempo" ? "tempo" : "meter") + " at bar 1",
                       Reporter::Note{music->first.location,
                                      "set it here, and changes by bar in its 'changes'"});
      }
    }
    if (scope->song) {
      scope->tempo = scope->song->tempo;
      scope->meter = scope->song->meter;
    } else if (music->second.is_map()) {
      // A broken block still counts beats by the tempo and meter it gives, so its mistakes are
      // not followed by one "no tempo" per step (the reporter says each mistake once); a tempo
      // or meter it lacks, or gives as a mistake, counts as 120 and 4/4 (said once already).
      const YamlNode* t = music->second.find("tempo");
      const YamlNode* m = music->second.find("meter");
      scope->tempo =
          t != nullptr ? parse_tempo(*t, reporter).value_or(kStandInTempo) : kStandInTempo;
      scope->meter =
          m != nullptr ? parse_meter(*m, reporter).value_or(kStandInMeter) : kStandInMeter;
    }
  } else {
    if (const YamlNode* t = f.root->find("tempo")) scope->tempo = parse_tempo(*t, reporter);
    if (const YamlNode* m = f.root->find("meter")) {
      scope->meter = parse_meter(*m, reporter);
    }
  }
  FileScope& ref = *scope;
  scopes_.emplace(f.path, std::move(scope));
  return {ref, true};
}

std::optional<std::uint32_t> ScopeChain::resolution_ms() const {
  for (auto it = chain_.rbegin(); it != chain_.rend(); ++it) {
    if ((*it)->resolution_ms) return (*it)->resolution_ms;
  }
  return std::nullopt;
}

std::optional<Tempo> ScopeChain::tempo() const {
  // While a song plays its map is the only one: an included file's own tempo is for checking
  // that file alone.
  if (!chain_.empty() && chain_.front()->song) return chain_.front()->tempo;
  for (auto it = chain_.rbegin(); it != chain_.rend(); ++it) {
    if ((*it)->tempo) return (*it)->tempo;
  }
  return std::nullopt;
}

std::optional<TimeSignature> ScopeChain::meter() const {
  if (!chain_.empty() && chain_.front()->song) return chain_.front()->meter;
  for (auto it = chain_.rbegin(); it != chain_.rend(); ++it) {
    if ((*it)->meter) return (*it)->meter;
  }
  return std::nullopt;
}

std::optional<double> ScopeChain::tolerance() const {
  for (auto it = chain_.rbegin(); it != chain_.rend(); ++it) {
    if ((*it)->tolerance) return (*it)->tolerance;
  }
  return std::nullopt;
}

const YamlNode* ScopeChain::find_section(const YamlNode& name, Reporter& reporter) const {
  if (!name.is_scalar()) {
    reporter.error(name.location, "'section' names a section of this file, e.g. 'section: nod'");
    return nullptr;
  }
  std::vector<std::string> known;
  for (auto it = chain_.rbegin(); it != chain_.rend(); ++it) {
    auto s = (*it)->sections.find(name.scalar);
    if (s != (*it)->sections.end()) return s->second;
    for (const auto& [n, list] : (*it)->sections) known.push_back(n);
  }
  reporter.unknown(name.location, "section", name.scalar, known);
  return nullptr;
}

std::optional<ExactMs> ScopeChain::exact_ms(const YamlNode& node, std::string_view what,
                                            Reporter& reporter) const {
  const std::optional<TimeValue> t = parse_time_node(node, what, reporter);
  if (!t) return std::nullopt;
  ExactMs ms = exact_amount(*t);
  if (t->unit == TimeUnit::Seconds) ms = ms * ExactMs(1000);
  if (t->unit == TimeUnit::Beats || t->unit == TimeUnit::Bars) {
    const std::optional<Tempo> tempo = this->tempo();
    if (!tempo) {
      report_no_tempo(node, reporter);
      return std::nullopt;
    }
    const std::optional<TimeSignature> bar = meter();
    if (t->unit == TimeUnit::Bars) {
      if (!bar) {
        report_no_meter(node, reporter);
        return std::nullopt;
      }
      ms = ms * ExactMs(bar->beats_per_bar);
    }
    ms = ms * beat_ms(*tempo, bar ? bar->beat_unit : 4);
  }
  return ms;
}

std::optional<std::uint32_t> ScopeChain::time_ms(const YamlNode& node, std::string_view what,
                                                 std::uint64_t max_ms, std::string_view too_long,
                                                 Reporter& reporter) const {
  auto exact = exact_ms(node, what, reporter);
  if (!exact) return std::nullopt;
  const double ms = exact->value();
  if (ms > static_cast<double>(max_ms)) {
    reporter.error(node.location, "'" + node.scalar + "' " + std::string(too_long));
    return std::nullopt;
  }
  return static_cast<std::uint32_t>(std::llround(ms));
}

const OutputGroup* ScopeChain::find_group(std::string_view name) const {
  for (auto it = chain_.rbegin(); it != chain_.rend(); ++it) {
    auto g = (*it)->groups.find(name);
    if (g != (*it)->groups.end()) return &g->second;
  }
  return nullptr;
}

std::vector<std::string> ScopeChain::group_names() const {
  std::vector<std::string> names;
  for (const FileScope* s : chain_) {
    for (const auto& [n, group] : s->groups) names.push_back(n);
  }
  return names;
}

const Pose* ScopeChain::find_pose(const YamlNode& name, Reporter& reporter) {
  for (auto it = chain_.rbegin(); it != chain_.rend(); ++it) {
    auto p = (*it)->poses.find(name.scalar);
    if (p != (*it)->poses.end()) return &p->second;
  }
  if (name.scalar == "home") {
    if (!home_) {
      home_ = std::make_unique<Pose>();
      for (std::size_t i : home_outputs_) {
        PositionEntry e;
        e.output = i;
        e.home = true;
        e.written = "home";
        home_->entries.push_back(e);
      }
    }
    return home_.get();
  }
  std::vector<std::string> names{"home"};
  for (const FileScope* s : chain_) {
    for (const auto& [n, pose] : s->poses) names.push_back(n);
  }
  reporter.unknown(name.location, "pose", name.scalar, names);
  return nullptr;
}

const std::vector<PositionEntry>* ScopeChain::move_entries(
    const YamlNode& target, std::string_view noun, const ParseEntries& parse,
    std::vector<PositionEntry>& inline_entries, std::optional<Reporter::Note>& note,
    Reporter& reporter) {
  if (target.is_scalar()) {
    const Pose* pose = find_pose(target, reporter);
    if (pose == nullptr) return nullptr;
    // The built-in home has no place in the file: its mistakes are reported at this move
    // (Reporter::report), so the note is that location.
    note = Reporter::Note{target.location, "in this move to pose '" + target.scalar + "'"};
    return &pose->entries;
  }
  if (target.is_map()) {
    inline_entries = parse(target, "in this move");
    return &inline_entries;
  }
  reporter.error(target.location, "'move' takes a pose name or a map of " + std::string(noun) +
                                      ": position, not " + std::string(kind_name(target)));
  return nullptr;
}

const LoadedFile* ScopeChain::load_include(const YamlNode& value, std::string_view example,
                                           CannotLoad cannot_load, FileLoader& loader,
                                           Reporter& reporter) {
  if (!value.is_scalar() || value.scalar.empty()) {
    reporter.error(value.location,
                   "'include' takes a file path, e.g. 'include: " + std::string(example) + "'");
    return nullptr;
  }
  const LoadedFile& current = *chain_.back()->file;
  const std::string path = resolve_include(current.path, value.scalar);
  for (std::size_t i = 0; i < chain_.size(); ++i) {
    if (chain_[i]->file->path != path) continue;
    std::string cycle;
    for (std::size_t j = i; j < chain_.size(); ++j) cycle += chain_[j]->file->path + " -> ";
    reporter.error(value.location, "include cycle: " + cycle + path);
    return nullptr;
  }
  if (reporter.include_depth() >= kMaxIncludeDepth) {
    reporter.error(value.location, "includes nest more than " + std::to_string(kMaxIncludeDepth) +
                                       " files deep; is there a runaway include chain?");
    return nullptr;
  }
  auto loaded = loader.load_included(path);
  if (!loaded) {
    reporter.error(value.location, cannot_load(path, loaded.error().message));
    return nullptr;
  }
  return *loaded;
}

void parse_poses(const YamlNode& poses, FileScope& scope, std::string_view not_a_map,
                 std::string_view pose_shape, const ScopeChain::ParseEntries& parse,
                 Reporter& reporter) {
  if (poses.kind == YamlNode::Kind::Null) return;
  if (!poses.is_map()) {
    reporter.error(poses.location, std::string(not_a_map));
    return;
  }
  for (const auto& [key, value] : poses.entries) {
    Pose pose;
    pose.at = key.location;
    if (!value.is_map()) {
      reporter.error(value.location,
                     "pose '" + key.scalar + "' must be a map of " + std::string(pose_shape));
    } else {
      pose.entries = parse(value, "in pose '" + key.scalar + "'");
    }
    scope.poses.emplace(key.scalar, std::move(pose));
  }
}

const YamlNode* file_root(const LoadedFile& f, Reporter& reporter) {
  if (!f.root) return nullptr;
  if (!f.root->is_map()) {
    reporter.error(f.root->location,
                   "a choreography file must be a map with 'robot' and 'sequence' keys");
    return nullptr;
  }
  return &*f.root;
}

bool check_included_robot(const YamlNode& root, const std::string& profile, Reporter& reporter) {
  const YamlNode* r = root.find("robot");
  if (r == nullptr) return true;
  auto name = included_robot_name(*r, reporter);
  if (!name || *name == profile) return true;
  reporter.error(r->location, "this file is for robot '" + *name +
                                  "' but is included by a file for '" + profile + "'");
  return false;
}

const YamlNode* find_sequence(const YamlNode& root, Reporter& reporter) {
  const YamlNode* sequence = root.find("sequence");
  if (sequence == nullptr) {
    reporter.error(root.location, "missing 'sequence': the list of steps to perform");
  }
  return sequence;
}

std::optional<TimeValue> parse_time_node(const YamlNode& node, std::string_view what,
                                         Reporter& reporter) {
  if (!node.is_scalar()) {
    reporter.error(node.location, std::string(what) + " must be a time such as 500ms, 1.5s or 2b");
    return std::nullopt;
  }
  auto t = parse_time(node.scalar);
  if (!t) {
    reporter.error(node.location, t.error().message);
    return std::nullopt;
  }
  if (t->amount > 1e9) {
    reporter.error(node.location, "'" + node.scalar + "' is far longer than any sequence");
    return std::nullopt;
  }
  return *t;
}

void report_no_tempo(const YamlNode& node, Reporter& reporter) {
  reporter.error(node.location, "'" + node.scalar +
                                    "' counts beats but no 'tempo' is set; add e.g. "
                                    "'tempo: 120' at the top of the file");
}

void report_no_meter(const YamlNode& node, Reporter& reporter) {
  reporter.error(node.location, "'" + node.scalar +
                                    "' counts bars but no 'meter' is set; add e.g. "
                                    "'meter: 4/4' at the top of the file");
}

std::optional<Tempo> parse_tempo(const YamlNode& node, Reporter& reporter) {
  std::string_view text = node.is_scalar() ? std::string_view(node.scalar) : "";
  const std::size_t equals = text.find('=');
  Tempo tempo;
  std::string_view number = text;
  if (equals != std::string_view::npos) {
    if (!parse_tempo_note(text.substr(0, equals), tempo.note_num, tempo.note_den)) {
      reporter.error(node.location,
                     "'tempo: " + node.scalar +
                         "': before '=' goes the note the tempo counts, a fraction of a whole "
                         "note or its name (whole, half, quarter, eighth, sixteenth, optionally "
                         "'dotted'), e.g. 'tempo: 3/8 = 60' or 'tempo: dotted quarter = 60'");
      return std::nullopt;
    }
    number = text.substr(equals + 1);
    while (!number.empty() && number.front() == ' ') number.remove_prefix(1);
  }
  if (number.size() > 3 && number.substr(number.size() - 3) == "bpm") number.remove_suffix(3);
  if (!node.is_scalar() || !parse_decimal(number, tempo.per_minute) || tempo.per_minute < 1 ||
      tempo.per_minute > 1000) {
    reporter.error(node.location,
                   equals != std::string_view::npos
                       ? "'tempo: " + node.scalar +
                             "': after '=' goes how many of that note a minute, between 1 and "
                             "1000, e.g. 'tempo: dotted quarter = 60'"
                       : "'tempo' must be beats per minute between 1 and 1000, e.g. 'tempo: 120'");
    return std::nullopt;
  }
  return tempo;
}

std::optional<TimeSignature> parse_meter(const YamlNode& node, Reporter& reporter) {
  const std::string text = node.is_scalar() ? node.scalar : "";
  const auto slash = text.find('/');
  double beats = 0, unit = 0;
  const bool ok = slash != std::string::npos &&
                  parse_decimal(std::string_view(text).substr(0, slash), beats) &&
                  parse_decimal(std::string_view(text).substr(slash + 1), unit) &&
                  beats == std::floor(beats) && beats >= 1 && beats <= 32 &&
                  (unit == 1 || unit == 2 || unit == 4 || unit == 8 || unit == 16 || unit == 32);
  if (!ok) {
    reporter.error(node.location,
                   "'meter' must be beats per bar over the beat's note value, e.g. 'meter: 3/4' "
                   "or 'meter: 6/8'");
    return std::nullopt;
  }
  return TimeSignature{static_cast<int>(beats), static_cast<int>(unit)};
}

}  // namespace seqc::compiler
