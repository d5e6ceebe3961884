// The step walk's shared pieces (step_walk.hpp): musical time, `at:`, meter changes and the
// tracks of `together` blocks; sections and their parameters are in sections.cpp.
#include "compiler/frontend/step_walk.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <iterator>
#include <sstream>
#include <tuple>
#include <utility>

#include "base/diagnostics.hpp"
#include "base/units.hpp"
#include "compiler/frontend/key_tables.hpp"
#include "compiler/frontend/music_section.hpp"
#include "compiler/frontend/step_parts.hpp"

namespace seqc::compiler {
namespace {

// "17.000 s": an instant or span to the millisecond, for `at: bar N` messages.
std::string seconds_text(ExactMs t) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f s", t.value() / 1000.0);
  return buf;
}

// "1 beat", "1.5 beats": how far a meter change is off its bar line.
std::string beats_text(ExactMs beats) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f", beats.value());
  std::string s = buf;
  while (s.back() == '0') s.pop_back();
  if (s.back() == '.') s.pop_back();
  return s + (s == "1" ? " beat" : " beats");
}

std::string format_exact_ms(ExactMs t) {
  const double ms = t.value();
  if (ms == std::floor(ms)) return std::to_string(static_cast<long long>(ms)) + "ms";
  return format_ms(ms);
}

// "10,000": a count in a message.
std::string with_commas(std::size_t n) {
  const std::string digits = std::to_string(n);
  std::string out;
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return out;
}

// "s0 -> s1 -> s2 -> ... -> s63 -> s64": a chain of section names, its middle left out when
// it is long (the ends say where it starts and where it ran away).
std::string chain_text(const std::vector<std::string_view>& names) {
  constexpr std::size_t kEnds = 3;
  std::string out;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (names.size() > 2 * kEnds + 1 && i >= kEnds && i < names.size() - kEnds) {
      if (i == kEnds) out += " -> ...";
      continue;
    }
    out += (i == 0 ? "" : " -> ") + std::string(names[i]);
  }
  return out;
}

}  // namespace

std::optional<ExactMs> musical_time(const TempoMap& map, const YamlNode& node,
                                    std::string_view what, ExactMs from, Reporter& reporter) {
  const std::optional<TimeValue> t = parse_time_node(node, what, reporter);
  if (!t) return std::nullopt;
  const bool musical = t->unit == TimeUnit::Beats || t->unit == TimeUnit::Bars;
  if (musical && map.bpm_at(from) <= 0) {
    report_no_tempo(node, reporter);
    return std::nullopt;
  }
  if (t->unit == TimeUnit::Bars && map.meter_at(from) <= 0) {
    report_no_meter(node, reporter);
    return std::nullopt;
  }
  const std::optional<ExactMs> end = map.after(from, exact_amount(*t), t->unit);
  if (!end) report_no_tempo(node, reporter);  // a stretch on the way has none
  return end;
}

std::optional<ExactMs> bar_position(const TempoMap& map, const YamlNode& at, Reporter& reporter) {
  // "bar N" or "bar N beat B", counted like a musician: bar 1 beat 1 is the start.
  std::vector<std::string> words;
  std::istringstream in(at.scalar);
  for (std::string w; in >> w;) words.push_back(w);
  double bar = 0, beat = 1;
  const bool ok = (words.size() == 2 || (words.size() == 4 && words[2] == "beat")) &&
                  parse_decimal(words[1], bar) && bar == std::floor(bar) && bar >= 1 &&
                  bar <= 1e6 && (words.size() == 2 || parse_decimal(words[3], beat)) && beat >= 1 &&
                  beat <= 1e6;
  if (!ok) {
    reporter.error(at.location,
                   "'at: " + at.scalar +
                       "' is not a position; write 'bar N' or 'bar N beat B' (counted from 1, "
                       "e.g. 'at: bar 9 beat 3'), or a time from the start of this list such "
                       "as 'at: 8bar'");
    return std::nullopt;
  }
  const TempoMap::Change& start = map.changes().front();
  if (start.bpm <= 0 || start.beats_per_bar <= 0) {
    reporter.error(at.location, "'at: " + at.scalar +
                                    "' counts bars from the start of the sequence; set "
                                    "'tempo' and 'meter' at the top of the file");
    return std::nullopt;
  }
  const ExactMs bar_index = ExactMs::from_double(bar - 1);
  const std::optional<ExactMs> bar_start = map.time_of_bar(bar_index);
  if (!bar_start) {
    report_no_tempo(at, reporter);
    return std::nullopt;
  }
  const int per_bar = map.meter_at(*bar_start);
  if (beat >= per_bar + 1) {
    reporter.error(at.location, "bar " + words[1] + " has " + std::to_string(per_bar) +
                                    " beats: 'beat " + words[3] + "' is past its end");
    return std::nullopt;
  }
  const std::optional<ExactMs> t = map.time_of_bar_beat(bar_index, ExactMs::from_double(beat - 1));
  if (!t) report_no_tempo(at, reporter);  // the tempo stops inside the bar
  return t;
}

std::optional<ExactMs> at_target(const TempoMap& map, const YamlNode& at_node, ExactMs now,
                                 ExactMs list_start, Reporter& reporter) {
  const YamlNode* at = &at_node;
  const bool position = at->is_scalar() && at->scalar.rfind("bar ", 0) == 0;
  std::optional<ExactMs> target = position ? bar_position(map, *at, reporter)
                                           : musical_time(map, *at, "'at'", list_start, reporter);
  if (!target) return std::nullopt;
  if (*target < now && position) {
    reporter.error(at->location, at->scalar + " is at " + seconds_text(*target) +
                                     " but this list is already at " + seconds_text(now) + " (" +
                                     seconds_text(now - *target) + " past it)");
    return std::nullopt;
  }
  if (*target < now) {
    reporter.error(at->location,
                   "'at: " + at->scalar + "' is " + format_exact_ms(now - *target) +
                       " in the past: the steps before it already run until " +
                       format_seconds(static_cast<std::uint64_t>((now - list_start).round())) +
                       " of this list");
    return std::nullopt;
  }
  return target;
}

bool change_meter(TempoMap& map, ExactMs now, TimeSignature meter, Location at,
                  std::string_view what, Reporter& reporter) {
  const int current = map.meter_at(now);
  if (current > 0 && map.bpm_at(now) > 0 &&
      (meter.beats_per_bar != current || meter.beat_unit != map.beat_unit_at(now))) {
    if (const std::optional<TempoMap::BarOffset> off = map.off_bar_line(now)) {
      reporter.error(at, std::string(what) + " must fall on a bar line, but here it is " +
                             beats_text(off->beats) + " into bar " + std::to_string(off->bar + 1) +
                             " (" + beats_text(ExactMs(current) - off->beats) + " before bar " +
                             std::to_string(off->bar + 2) + ")");
      return false;
    }
  }
  map.set_meter(now, meter);
  return true;
}

void TrackClaims::begin_track(std::string name, Location at) {
  blocks_.back().track = Track{std::move(name), at, {}};
}

void TrackClaims::end_block() { blocks_.pop_back(); }

bool TrackClaims::claim(std::size_t output, std::string_view who, std::string_view verb,
                        std::string_view rule, Location at, Reporter& reporter) {
  // One track of each running block: the innermost block is checked first (its tracks are
  // the closest places to name).
  for (auto block = blocks_.rbegin(); block != blocks_.rend(); ++block) {
    auto it = block->claimed.find(output);
    if (it == block->claimed.end() || it->second.first == block->track.name) continue;
    reporter.error(
        at,
        std::string(who) + " " + std::string(verb) + " in two tracks, '" + it->second.first +
            "' and '" + block->track.name + "'; " + std::string(rule),
        Reporter::Note{it->second.second, std::string(who) + " " + std::string(verb) +
                                              " in track '" + it->second.first + "' here"});
    return false;
  }
  for (Block& block : blocks_) {
    block.claimed.try_emplace(output, block.track.name, at);
    std::vector<std::size_t>& outputs = block.track.outputs;
    if (std::find(outputs.begin(), outputs.end(), output) == outputs.end()) {
      outputs.push_back(output);
    }
  }
  return true;
}

bool TrackClaims::outside_tracks(const YamlNode& value, std::string_view verb,
                                 Reporter& reporter) const {
  if (blocks_.empty()) return true;
  const Track& track = blocks_.front().track;
  reporter.error(value.location,
                 "'" + std::string(verb) +
                     "' inside a 'together' track would change the other tracks' " +
                     (verb == "tempo" ? "beats" : "bars") +
                     " too; "
                     "move it out of the 'together', before or after it",
                 Reporter::Note{track.at, "in track '" + track.name + "' of this 'together'"});
  return false;
}

// ---- the walker ------------------------------------------------------------------------------

StepWalker::StepWalker(FileLoader& loader, Reporter& reporter, const StepTable& table,
                       std::vector<std::size_t> home_outputs, std::size_t outputs)
    : loader_(loader), reporter_(reporter), scopes_(std::move(home_outputs)), table_(table) {
  timeline_.resize(outputs);
}

bool StepWalker::is_verb(std::string_view key, const YamlNode& /*step*/) const {
  static constexpr std::string_view kShared[] = {"repeat",   "include", "section",
                                                 "together", "tempo",   "meter"};
  return std::find(std::begin(kShared), std::end(kShared), key) != std::end(kShared) ||
         std::find(table_.verbs.begin(), table_.verbs.end(), key) != table_.verbs.end();
}

void StepWalker::run_sequence(const YamlNode& root, FileScope& scope, const YamlNode& sequence,
                              bool is_main) {
  TempoMap& music = timeline_.tempo_map;
  if (is_main) {
    timeline_.song = scope.song;
    timeline_.song_file = scope.song_file;
    music = scope.song
                ? song_tempo_map(*scope.song)
                : TempoMap(scope.tempo.value_or(Tempo{}), scope.meter.value_or(TimeSignature{}));
  } else {
    check_included_music(root);
  }
  // An included file's own tempo and meter hold while its steps run (not while a song plays:
  // its map is the only one). The meter first, so that the file's tempo counts its own beat.
  const ExactMs outer_beat = music.beat_ms_at(now_);
  const TimeSignature outer_meter{music.meter_at(now_), music.beat_unit_at(now_)};
  const bool own_music = !is_main && !timeline_.song;
  bool own_meter = own_music && scope.meter && *scope.meter != outer_meter;
  if (own_meter) {
    const YamlNode& meter = *root.find("meter");
    own_meter = change_meter(*scope.meter, meter.location, "'meter: " + meter.scalar + "'");
  }
  const bool own_tempo = own_music && scope.tempo &&
                         beat_ms(*scope.tempo, music.beat_unit_at(now_)) != music.beat_ms_at(now_);
  if (own_tempo) music.set_tempo(now_, *scope.tempo);
  scopes_.push(scope);
  run_steps(sequence, "'sequence'");
  scopes_.pop();
  if (is_main) warn_unperformed_sections(scope);
  if (own_meter && !reporter_.include_sites().empty()) {
    change_meter(outer_meter, reporter_.include_sites().back(),
                 "the including file's meter, resuming after this include,");
  }
  if (own_tempo) music.set_beat_ms(now_, outer_beat);
}

void StepWalker::run_steps(const YamlNode& list, std::string_view what) {
  lists_.push_back({now_, std::nullopt});
  for (const YamlNode& step : step_items(list, what, reporter_)) {
    if (halted()) break;
    run_step(step);
  }
  lists_.pop_back();
}

void StepWalker::run_step(const YamlNode& step) {
  if (times_ == nullptr) {
    walk_step(step);
    return;
  }
  timed_steps_.push_back(times_->begin(step.location, now_));
  walk_step(step);
  times_->end(timed_steps_.back(), now_);
  timed_steps_.pop_back();
}

void StepWalker::walk_step(const YamlNode& step) {
  if (++steps_walked_ > kMaxWalkedSteps) {
    halt(step.location, "the sequence walks more than " + with_commas(kMaxWalkedSteps) +
                            " steps, each counted again every time a section, include or repeat "
                            "runs it; is there a runaway fan-out of sections or includes?");
    return;
  }
  if (!step.is_map()) {
    reporter_.error(step.location, "a step must be a map such as " + std::string(table_.example) +
                                       ", not " + std::string(kind_name(step)));
    return;
  }
  const auto combinable = [this](std::string_view verb) {
    return std::find(table_.combinable.begin(), table_.combinable.end(), verb) !=
           table_.combinable.end();
  };
  const YamlNode* verb = nullptr;
  for (const auto& [key, value] : step.entries) {
    if (!is_verb(key.scalar, step)) continue;
    if (verb == nullptr) {
      verb = &key;
    } else if (!combinable(verb->scalar) || !combinable(key.scalar)) {
      reporter_.error(key.location, "a step does one thing: '" + key.scalar +
                                        "' cannot be combined with '" + verb->scalar +
                                        "'; make it a separate step");
      return;
    }
  }
  if (verb == nullptr) {
    if (reporter_.check_keys(step, table_.step_keys, "in a step")) {
      reporter_.error(step.location, std::string(table_.needs_one_of));
    }
    return;
  }
  const std::string& name = verb->scalar;
  const YamlNode& value = *step.find(name);
  if (name == "repeat") {
    if (reporter_.check_keys(step, kRepeatStepKeys, "in a repeat step") && apply_at(step)) {
      repeat_step(step, value);
    }
  } else if (name == "include") {
    if (reporter_.check_keys(step, kIncludeStepKeys, "in an include step") && apply_at(step)) {
      include_step(value);
    }
  } else if (name == "section") {
    if (reporter_.check_keys(step, kSectionStepKeys, "in a section step") && apply_at(step)) {
      section_step(step, value);
    }
  } else if (name == "together") {
    if (reporter_.check_keys(step, kTogetherStepKeys, "in a together step") && apply_at(step)) {
      together_step(step, value);
    }
  } else if (name == "tempo") {
    if (reporter_.check_keys(step, {"tempo"}, "in a tempo step")) tempo_step(value);
  } else if (name == "meter") {
    if (reporter_.check_keys(step, {"meter"}, "in a meter step")) meter_step(value);
  } else {
    own_step(*verb, step);
  }
}

bool StepWalker::apply_at(const YamlNode& step) {
  const YamlNode* at = step.find("at");
  if (at == nullptr) return true;
  const std::optional<ExactMs> target =
      at_target(timeline_.tempo_map, *at, now_, lists_.back().start, reporter_);
  if (!target) return false;
  if (*target > now_ && !hold_until(*target, *at)) return false;
  if (times_ != nullptr && !timed_steps_.empty()) times_->started(timed_steps_.back(), *target);
  // A cue is drawn wherever it falls, also where the steps before it already end there.
  timeline_.markers.push_back({*target, "at " + at->scalar, at->location});
  return true;
}

std::optional<ExactMs> StepWalker::musical_time(const YamlNode& node, std::string_view what,
                                                ExactMs from) {
  return compiler::musical_time(timeline_.tempo_map, node, what, from, reporter_);
}

bool StepWalker::change_meter(TimeSignature meter, Location at, std::string_view what) {
  return compiler::change_meter(timeline_.tempo_map, now_, meter, at, what, reporter_);
}

bool StepWalker::open_block(Location at, std::string_view verb) {
  if (blocks_deep_ >= kMaxBlockDepth) {
    const std::string through =
        section_names_.empty() ? "" : ", through sections " + chain_text(section_names_);
    reporter_.error(at, "this '" + std::string(verb) + "' nests more than " +
                            std::to_string(kMaxBlockDepth) +
                            " blocks deep ('together', 'repeat' and 'mirror' inside each other" +
                            through + "); is there a runaway chain of sections or includes?");
    halted_ = true;
    return false;
  }
  ++blocks_deep_;
  return true;
}

void StepWalker::halt(Location at, std::string message) {
  reporter_.error_with_notes(at, std::move(message), reporter_.chain());
  halted_ = true;
}

void StepWalker::repeat_step(const YamlNode& step, const YamlNode& value) {
  const auto repeat = parse_repeat(step, value, reporter_);
  if (!repeat) return;
  if (!open_block(step.location, "repeat")) return;
  const std::unique_ptr<RepeatBudget> budget = repeat_budget(step, repeat->times);
  performances_.open(now_, step.location, Performances::Kind::Repeat, nullptr, repeat->times);
  for (long long i = 0; i < repeat->times; ++i) {
    // The budget first: a walk stopped inside the last pass still has the passes left counted.
    if (!budget->before_pass(i) || halted()) break;
    const std::size_t errors_before = reporter_.errors_reported();
    reporter_.push_pass(step.location, i + 1, repeat->times);
    performances_.pass(now_);
    run_steps(*repeat->body, "'do'");
    reporter_.pop_pass();
    // A pass with mistakes would only repeat them in the passes after it (and nested repeats
    // would never end).
    if (reporter_.errors_reported() > errors_before || !budget->after_pass(i)) break;
  }
  performances_.close(now_);
  close_block();
}

void StepWalker::include_step(const YamlNode& value) {
  if (++includes_walked_ > kMaxIncludesWalked) {
    halt(value.location, "the sequence includes files more than " +
                             with_commas(kMaxIncludesWalked) +
                             " times, each include counted again every time a section, include "
                             "or repeat runs it; is there a runaway fan-out of includes?");
    return;
  }
  const LoadedFile* loaded = scopes_.load_include(value, table_.include_example,
                                                  table_.cannot_include, loader_, reporter_);
  if (loaded == nullptr) return;
  reporter_.push_include(value.location);
  performances_.open(now_, value.location, Performances::Kind::Include);
  run_file(*loaded, false);
  performances_.close(now_);
  reporter_.pop_include();
}

void StepWalker::section_step(const YamlNode& step, const YamlNode& value) {
  if (section_names_.size() >= kMaxSectionDepth) {
    std::vector<std::string_view> chain = section_names_;
    chain.push_back(value.scalar);
    reporter_.error(value.location,
                    "sections perform sections more than " + std::to_string(kMaxSectionDepth) +
                        " deep: " + chain_text(chain) + "; is there a runaway chain of sections?");
    halted_ = true;
    return;
  }
  run_section(step, value, scopes_, sections_running_, reporter_,
              [&](const YamlNode& steps, const std::string& what) {
                timeline_.markers.push_back({now_, "section " + value.scalar, value.location});
                sections_performed_.insert(sections_running_.back());
                section_names_.push_back(value.scalar);
                performances_.open(now_, value.location, Performances::Kind::Section,
                                   &value.scalar);
                run_steps(steps, what);
                performances_.close(now_);
                section_names_.pop_back();
              });
}

void StepWalker::warn_unperformed_sections(const FileScope& main) {
  if (halted() || reporter_.errors_reported() > 0) return;
  std::vector<std::pair<Location, std::string>> unperformed;
  for (const auto& [name, steps] : main.sections) {
    if (sections_performed_.count(steps) != 0) continue;
    auto at = main.section_at.find(name);
    if (at != main.section_at.end()) unperformed.emplace_back(at->second, name);
  }
  std::sort(unperformed.begin(), unperformed.end(), [](const auto& a, const auto& b) {
    return std::tie(a.first.line, a.first.column) < std::tie(b.first.line, b.first.column);
  });
  for (const auto& [at, name] : unperformed) {
    reporter_.warning(at, "section '" + name + "' is defined but never performed");
  }
}

void StepWalker::together_step(const YamlNode& step, const YamlNode& tracks) {
  if (!tracks.is_map() || tracks.entries.empty()) {
    reporter_.error(tracks.location, "'together' takes named tracks, each a list of steps, e.g. " +
                                         std::string(table_.together_example));
    return;
  }
  if (!open_block(step.location, "together")) return;
  const std::unique_ptr<BlockRun> run = block_run(step);
  const ExactMs start = now_;
  ExactMs longest = start;
  claims_.begin_block();
  for (const auto& [name, list] : tracks.entries) {
    claims_.begin_track(name.scalar, name.location);
    now_ = start;
    run->track_begins();
    run_steps(list, "track '" + name.scalar + "'");
    run->track_ends();
    longest = std::max(longest, now_);
    if (halted()) break;
  }
  claims_.end_block();
  now_ = longest;
  run->block_ends(start, longest);
  close_block();
}

void StepWalker::check_included_music(const YamlNode& root) {
  for (const YamlEntry& e : root.entries) {
    if (e.first.scalar != "music") continue;
    reporter_.error(e.first.location,
                    "'music' belongs in the main file: the song plays from its "
                    "first step");
  }
}

bool StepWalker::song_owns(const YamlNode& value, std::string_view key) {
  if (!timeline_.song) return false;
  reporter_.error(value.location,
                  "'" + std::string(key) + ": " + value.scalar +
                      "' while the song plays: its tempo map is the only one",
                  Reporter::Note{timeline_.song->at,
                                 "the song's 'music' sets tempo and meter, with changes by bar "
                                 "in its 'changes'"});
  return true;
}

void StepWalker::tempo_step(const YamlNode& value) {
  if (song_owns(value, "tempo")) return;
  if (!claims_.outside_tracks(value, "tempo", reporter_)) return;
  if (auto tempo = parse_tempo(value, reporter_)) {
    timeline_.tempo_map.set_tempo(now_, *tempo);
    timeline_.markers.push_back({now_, "tempo " + value.scalar, value.location});
  }
}

void StepWalker::meter_step(const YamlNode& value) {
  if (song_owns(value, "meter")) return;
  if (!claims_.outside_tracks(value, "meter", reporter_)) return;
  const std::optional<TimeSignature> meter = parse_meter(value, reporter_);
  if (meter && change_meter(*meter, value.location, "'meter: " + value.scalar + "'")) {
    timeline_.markers.push_back({now_, "meter " + value.scalar, value.location});
  }
}

}  // namespace seqc::compiler
