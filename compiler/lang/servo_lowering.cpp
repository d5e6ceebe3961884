// The servo-controller front end: files, step lists and the structural steps. Motion steps
// (move, wait, through) are in servo_motion.cpp; fitting the finished timeline into actions is
// compiler/fitting/.
#include "compiler/lang/servo_lowering.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <sstream>
#include <string_view>
#include <utility>
#include <vector>

#include "compiler/fitting/fitter.hpp"
#include "compiler/lang/servo_lowering_state.hpp"
#include "compiler/lang/step_parts.hpp"
#include "compiler/source/units.hpp"
#include "runtime/protocol/group_download.hpp"

namespace seqc::compiler {
namespace {

std::uint64_t saturating_add(std::uint64_t a, std::uint64_t b) {
  return a > std::numeric_limits<std::uint64_t>::max() - b
             ? std::numeric_limits<std::uint64_t>::max()
             : a + b;
}

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

// A section parameter's name: what may follow `$`.
bool parameter_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_'; }
bool is_parameter_name(std::string_view name) {
  return !name.empty() && std::isdigit(static_cast<unsigned char>(name[0])) == 0 &&
         std::all_of(name.begin(), name.end(), parameter_char);
}

bool mentions_parameter(const YamlNode& node) {
  if (node.scalar.find('$') != std::string::npos) return true;
  for (const YamlNode& item : node.items) {
    if (mentions_parameter(item)) return true;
  }
  for (const YamlEntry& e : node.entries) {
    if (mentions_parameter(e.first) || mentions_parameter(e.second)) return true;
  }
  return false;
}

// Every `$name` and `${name}` in `node`'s keys and values replaced by the parameter's text; the
// names not in `values` go to `unknown` with where they are written.
void put_in_parameters(YamlNode& node,
                       const std::map<std::string, std::string, std::less<>>& values,
                       std::vector<std::pair<Location, std::string>>& unknown) {
  if (node.scalar.find('$') != std::string::npos) {
    std::string out;
    const std::string& in = node.scalar;
    for (std::size_t i = 0; i < in.size();) {
      const bool braced = in[i] == '$' && i + 1 < in.size() && in[i + 1] == '{';
      std::size_t from = i + (braced ? 2 : 1), to = from;
      while (in[i] == '$' && to < in.size() && parameter_char(in[to])) ++to;
      if (in[i] != '$' || to == from || (braced && (to >= in.size() || in[to] != '}'))) {
        out += in[i++];
        continue;
      }
      const std::string name = in.substr(from, to - from);
      auto it = values.find(name);
      if (it == values.end()) {
        unknown.emplace_back(node.location, name);
      } else {
        out += it->second;
      }
      i = to + (braced ? 1 : 0);
    }
    node.scalar = std::move(out);
  }
  for (YamlNode& item : node.items) put_in_parameters(item, values, unknown);
  for (YamlEntry& e : node.entries) {
    put_in_parameters(e.first, values, unknown);
    put_in_parameters(e.second, values, unknown);
  }
}

std::string format_exact_ms(ExactMs t) {
  const double ms = t.value();
  if (ms == std::floor(ms)) return std::to_string(static_cast<long long>(ms)) + "ms";
  return format_ms(ms);
}

}  // namespace

ServoLowering::ServoLowering(const Robot& robot, FileLoader& loader, Reporter& reporter)
    : robot_(robot),
      loader_(loader),
      reporter_(reporter),
      scopes_(robot.home_servos),
      pos_(robot.info.servos.size()) {
  timeline_.resize(robot.info.servos.size());
}

ServoProgram ServoLowering::run(const LoadedFile& main) {
  run_file(main, true);
  ServoProgram program;
  program.robot = robot_.info;
  finish(program);
  return program;
}

void ServoLowering::finish(ServoProgram& program) {
  timeline_.end = now_;
  // A file with mistakes makes no program: fitting it would only cost time (a long, slow curve
  // took seconds; found by the check fuzzer).
  if (reporter_.errors_reported() > 0) return;
  if (over_budget_at_) {
    // Already more actions than a group holds before fitting (each step needs at least its
    // count): fitting tens of thousands of steps would only cost time.
    reporter_.error(*over_budget_at_, "the sequence needs at least " +
                                          std::to_string(min_actions_) + "/" +
                                          std::to_string(capacity()) + " actions; " +
                                          group_capacity_text(robot_.profile));
    return;
  }
  FitResult fit = fit_timeline(timeline_);
  const std::uint64_t needed = std::max<std::uint64_t>(fit.actions.size(), min_actions_);
  if (needed > capacity()) {
    const Location at = fit.actions.size() > capacity() ? fit.actions[capacity()].source
                                                        : fit.actions.back().source;
    reporter_.error(at, "the sequence needs " + std::string(truncated_ ? "at least " : "") +
                            std::to_string(needed) + "/" + std::to_string(capacity()) +
                            " actions; " + group_capacity_text(robot_.profile));
    fit.actions.resize(std::min<std::size_t>(fit.actions.size(), capacity()));
  } else if (fit.actions.empty() && sequence_at_ && reporter_.errors_reported() == 0) {
    reporter_.error(*sequence_at_, "the sequence makes no actions; a group needs at least one");
  }
  // One warning per curve: its worst miss, naming every servo that misses it (each 20ms
  // action that falls short is a shortfall of its own, the same fact many times over).
  std::vector<bool> told(fit.shortfalls.size(), false);
  for (std::size_t i = 0; i < fit.shortfalls.size(); ++i) {
    if (told[i]) continue;
    const FitShortfall& first = fit.shortfalls[i];
    FitShortfall worst = first;
    std::vector<std::size_t> servos;
    for (std::size_t j = i; j < fit.shortfalls.size(); ++j) {
      const FitShortfall& s = fit.shortfalls[j];
      if (told[j] || s.where != first.where || s.tolerance != first.tolerance) continue;
      told[j] = true;
      if (std::find(servos.begin(), servos.end(), s.servo) == servos.end()) {
        servos.push_back(s.servo);
      }
      if (s.error > worst.error) worst = s;
    }
    // A curve always has a segment; should one not, the warning still points into the file.
    const Location where =
        first.where.file != kNoFile ? first.where : sequence_at_.value_or(Location{0, 1, 1});
    std::string who;
    for (std::size_t servo : servos) {
      who += (who.empty() ? "'" : ", '") + robot_.info.servos[servo].name + "'";
    }
    const std::string message =
        servos.size() == 1
            ? "even 20ms actions cannot keep " + who + " within " + format_units(worst.tolerance) +
                  " of this curve: it is " + format_units(worst.error) + " off at " +
                  format_seconds(worst.at_ms)
            : "even 20ms actions cannot keep servos " + who + " within " +
                  format_units(worst.tolerance) + " of this curve: up to " +
                  format_units(worst.error) + " off ('" + robot_.info.servos[worst.servo].name +
                  "' at " + format_seconds(worst.at_ms) + ")";
    reporter_.warning(where, message);
    for (std::size_t servo : servos) {
      timeline_.warnings.push_back({static_cast<double>(worst.at_ms), servo, message});
    }
  }
  for (const FittedAction& a : fit.actions) {
    Keyframe k;
    k.start_ms = a.start_ms;
    k.time_ms = static_cast<std::uint16_t>(a.time_ms);
    k.source = a.source;
    for (const FittedTarget& t : a.targets) {
      k.targets.push_back(
          {robot_.info.servos[t.servo].id, static_cast<std::uint16_t>(std::max(0, t.position))});
    }
    std::sort(k.targets.begin(), k.targets.end(),
              [](const lsc::ServoTarget& x, const lsc::ServoTarget& y) { return x.id < y.id; });
    program.keyframes.push_back(std::move(k));
  }
  program.fit_error = fit.max_error;
  program.fit_error_at_ms = fit.max_error_at_ms;
  program.fit_error_servo =
      robot_.info.servos.empty() ? std::string() : robot_.info.servos[fit.max_error_servo].name;
  program.timeline = std::move(timeline_);
}

// ---- files and scopes -----------------------------------------------------------------------

void ServoLowering::run_file(const LoadedFile& f, bool is_main) {
  const YamlNode* map = file_root(f, reporter_);
  if (map == nullptr) return;
  const YamlNode& root = *map;
  reporter_.check_keys(root,
                       {"robot", "tempo", "meter", "resolution", "tolerance", "poses", "sections",
                        "sequence", "name", "description"},
                       "at the top level");
  reporter_.check_free_text(root);
  if (!is_main && !check_included_robot(root, robot_.info.profile, reporter_)) {
    return;  // its steps would only add errors about servos this robot lacks
  }
  FileScope& scope = scope_for(f);
  const YamlNode* sequence = find_sequence(root, reporter_);
  if (sequence == nullptr) return;
  TempoMap& music = timeline_.tempo_map;
  if (is_main) {
    sequence_at_ = sequence->location;
    music = TempoMap(scope.tempo.value_or(0), scope.beats_per_bar.value_or(0));
  }
  // An included file's own tempo and meter hold while its steps run.
  const double outer_bpm = music.bpm_at(now_);
  const int outer_meter = music.meter_at(now_);
  const bool own_tempo = !is_main && scope.tempo && *scope.tempo != outer_bpm;
  bool own_meter = !is_main && scope.beats_per_bar && *scope.beats_per_bar != outer_meter;
  if (own_tempo) music.set_tempo(now_, *scope.tempo);
  if (own_meter) {
    const YamlNode& meter = *root.find("meter");
    own_meter = change_meter(*scope.beats_per_bar, meter.location, "'meter: " + meter.scalar + "'");
  }
  scopes_.push(scope);
  run_steps(*sequence, "'sequence'");
  scopes_.pop();
  if (own_meter && !reporter_.include_sites().empty()) {
    change_meter(outer_meter, reporter_.include_sites().back(),
                 "the including file's meter, resuming after this include,");
  }
  if (own_tempo) music.set_tempo(now_, outer_bpm);
}

FileScope& ServoLowering::scope_for(const LoadedFile& f) {
  auto [scope, fresh] = scopes_.open(f, reporter_);
  if (!fresh) return scope;
  const YamlNode& root = *f.root;
  scopes_.push(scope);  // so this file's tempo, meter and poses apply while it is read
  if (const YamlNode* p = root.find("poses")) {
    compiler::parse_poses(
        *p, scope, "'poses' must be a map of pose names to servo positions",
        "servo: position, e.g. {claw: 500}",
        [this](const YamlNode& map, const std::string& where) {
          std::vector<PositionEntry> entries = parse_positions(map, where);
          for (const PositionEntry& e : entries) {
            if (!e.value.relative) {
              check_limits(e, e.output, absolute_units(e, e.output, false), {});
            }
          }
          return entries;
        },
        reporter_);
  }
  if (const YamlNode* r = root.find("resolution")) {
    auto ms =
        scopes_.time_ms(*r, "'resolution'", 30000, "is longer than an action can last", reporter_);
    if (ms && *ms < lsc::kMinActionMs) {
      reporter_.error(r->location, "resolution " + std::to_string(*ms) +
                                       "ms is below the controller's minimum of 20ms per action");
    } else if (ms) {
      scope.resolution_ms = *ms;
    }
  }
  if (const YamlNode* t = root.find("tolerance")) scope.tolerance = parse_tolerance(*t);
  if (const YamlNode* s = root.find("sections")) {
    if (!s->is_map()) {
      reporter_.error(s->location, "'sections' must be a map of section names to step lists");
    } else {
      for (const auto& [name, list] : s->entries) scope.sections[name.scalar] = &list;
    }
  }
  scopes_.pop();
  return scope;
}

// ---- step lists and structural steps ----------------------------------------------------------

void ServoLowering::run_steps(const YamlNode& list, std::string_view what) {
  lists_.push_back({now_, std::nullopt});
  for (const YamlNode& step : step_items(list, what, reporter_)) run_step(step);
  lists_.pop_back();
}

void ServoLowering::run_step(const YamlNode& step) {
  static constexpr std::string_view kVerbs[] = {"move",    "wait",   "through",  "repeat",
                                                "include", "mirror", "section",  "together",
                                                "tempo",   "meter",  "tolerance"};
  if (!step.is_map()) {
    reporter_.error(step.location, "a step must be a map such as 'move: home' or 'wait: 1s', not " +
                                       std::string(kind_name(step)));
    return;
  }
  const YamlNode* verb_key = nullptr;
  const YamlNode* verb_value = nullptr;
  for (const auto& [key, value] : step.entries) {
    // 'tolerance' is a verb only on its own: on a move or through it is a setting.
    if (key.scalar == "tolerance" && step.entries.size() > 1) continue;
    for (std::string_view v : kVerbs) {
      if (key.scalar != v) continue;
      if (verb_key != nullptr) {
        reporter_.error(key.location, "a step does one thing: '" + key.scalar +
                                          "' cannot be combined with '" + verb_key->scalar +
                                          "'; make it a separate step");
        return;
      }
      verb_key = &key;
      verb_value = &value;
    }
  }
  if (verb_key == nullptr) {
    if (reporter_.check_keys(
            step,
            {"move", "wait", "through", "repeat", "include", "mirror", "section", "together",
             "tempo", "meter", "tolerance", "time", "ease", "steps", "do", "with", "at"},
            "in a step")) {
      reporter_.error(step.location,
                      "a step needs one of: move, wait, through, repeat, include, mirror, "
                      "section, together, tempo, meter, tolerance");
    }
    return;
  }
  const std::string& verb = verb_key->scalar;
  if (verb == "move") {
    // Every mistake of the step is reported, so unknown keys do not stop the checks.
    const bool keys_ok = reporter_.check_keys(
        step, {"move", "time", "ease", "steps", "tolerance", "at"}, "in a move step");
    if (apply_at(step)) move_step(step, *verb_value, keys_ok);
  } else if (verb == "wait") {
    reporter_.check_keys(step, {"wait", "at"}, "in a wait step");
    if (apply_at(step)) wait_step(step, *verb_value);
  } else if (verb == "through") {
    reporter_.check_keys(step, {"through", "tolerance", "at"}, "in a through step");
    if (apply_at(step)) through_step(step, *verb_value);
  } else if (verb == "repeat") {
    if (reporter_.check_keys(step, {"repeat", "do", "at"}, "in a repeat step") && apply_at(step)) {
      repeat_step(step, *verb_value);
    }
  } else if (verb == "include") {
    if (reporter_.check_keys(step, {"include", "at"}, "in an include step") && apply_at(step)) {
      include_step(*verb_value);
    }
  } else if (verb == "mirror") {
    if (reporter_.check_keys(step, {"mirror", "at"}, "in a mirror step") && apply_at(step)) {
      mirror_step(step, *verb_value);
    }
  } else if (verb == "section") {
    if (reporter_.check_keys(step, {"section", "with", "at"}, "in a section step") &&
        apply_at(step)) {
      section_step(step, *verb_value);
    }
  } else if (verb == "together") {
    if (reporter_.check_keys(step, {"together", "at"}, "in a together step") && apply_at(step)) {
      together_step(step, *verb_value);
    }
  } else if (verb == "tempo") {
    if (reporter_.check_keys(step, {"tempo"}, "in a tempo step")) tempo_step(*verb_value);
  } else if (verb == "meter") {
    if (reporter_.check_keys(step, {"meter"}, "in a meter step")) meter_step(*verb_value);
  } else {
    tolerance_step(*verb_value);
  }
}

bool ServoLowering::apply_at(const YamlNode& step) {
  const YamlNode* at = step.find("at");
  if (at == nullptr) return true;
  const bool position = at->is_scalar() && at->scalar.rfind("bar ", 0) == 0;
  std::optional<ExactMs> target =
      position ? bar_position(*at) : musical_time(*at, "'at'", lists_.back().start);
  if (!target) return false;
  if (*target < now_ && position) {
    reporter_.error(at->location, at->scalar + " is at " + seconds_text(*target) +
                                      " but this list is already at " + seconds_text(now_) + " (" +
                                      seconds_text(now_ - *target) + " past it)");
    return false;
  }
  if (*target < now_) {
    reporter_.error(
        at->location,
        "'at: " + at->scalar + "' is " + format_exact_ms(now_ - *target) +
            " in the past: the steps before it already run until " +
            format_seconds(static_cast<std::uint64_t>((now_ - lists_.back().start).round())) +
            " of this list");
    return false;
  }
  // A cue is drawn wherever it falls, also where the steps before it already end there.
  timeline_.markers.push_back({*target, "at " + at->scalar, at->location});
  if (*target > now_) {
    const bool known = std::any_of(pos_.begin(), pos_.end(), [](auto& p) { return p.has_value(); });
    // In a track another track may be moving meanwhile (together_step checks that one does).
    if (!known && track_ == nullptr) {
      reporter_.error(at->location,
                      "nothing to hold until 'at': no servo has a position yet; start with a "
                      "move");
      return false;
    }
    // The hold is at least one action per 30 s (a far position must not reach the fitter).
    const auto gap = static_cast<std::uint64_t>((*target - now_).value());
    count_actions(std::max<std::uint64_t>(1, (gap + lsc::kMaxActionMs - 1) / lsc::kMaxActionMs),
                  at->location);
    now_ = *target;
  }
  return true;
}

std::optional<ExactMs> ServoLowering::bar_position(const YamlNode& at) {
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
    reporter_.error(at.location,
                    "'at: " + at.scalar +
                        "' is not a position; write 'bar N' or 'bar N beat B' (counted from 1, "
                        "e.g. 'at: bar 9 beat 3'), or a time from the start of this list such "
                        "as 'at: 8bar'");
    return std::nullopt;
  }
  const TempoMap& map = timeline_.tempo_map;
  const TempoMap::Change& start = map.changes().front();
  if (start.bpm <= 0 || start.beats_per_bar <= 0) {
    reporter_.error(at.location, "'at: " + at.scalar +
                                     "' counts bars from the start of the sequence; set "
                                     "'tempo' and 'meter' at the top of the file");
    return std::nullopt;
  }
  const std::optional<ExactMs> first = map.beat_of_bar(ExactMs::from_double(bar - 1));
  const std::optional<ExactMs> bar_start = first ? map.time_of_beat(*first) : std::nullopt;
  if (!bar_start) {
    report_no_tempo(at, reporter_);
    return std::nullopt;
  }
  const int per_bar = map.meter_at(*bar_start);
  if (beat >= per_bar + 1) {
    reporter_.error(at.location, "bar " + words[1] + " has " + std::to_string(per_bar) +
                                     " beats: 'beat " + words[3] + "' is past its end");
    return std::nullopt;
  }
  return map.time_of_beat(*first + ExactMs::from_double(beat - 1));
}

void ServoLowering::repeat_step(const YamlNode& step, const YamlNode& value) {
  const auto repeat = parse_repeat(step, value, reporter_);
  if (!repeat) return;
  std::uint64_t per_pass = 0;
  for (long long i = 0; i < repeat->times; ++i) {
    if (i > 0 && min_actions_ > capacity()) {  // already too long: count, do not expand
      const auto rest = static_cast<std::uint64_t>(repeat->times - i);
      min_actions_ = saturating_add(min_actions_, per_pass > 0 && rest > UINT64_MAX / per_pass
                                                      ? UINT64_MAX
                                                      : rest * per_pass);
      truncated_ = true;
      break;
    }
    const std::uint64_t before = min_actions_;
    const std::size_t errors_before = reporter_.errors_reported();
    run_steps(*repeat->body, "'do'");
    per_pass = min_actions_ - before;
    // A pass with mistakes makes no actions to count, and the passes after it would only repeat
    // them: 65535 nested six deep would never end (found by hostile_bench).
    if (reporter_.errors_reported() > errors_before || per_pass == 0) break;
  }
}

void ServoLowering::mirror_step(const YamlNode& step, const YamlNode& body) {
  if (!robot_.has_mirror_table) {
    reporter_.error(step.location,
                    "'mirror' needs a mirror table in the robot section, e.g. "
                    "'mirror: {left_arm: right_arm}' under 'robot:'");
    return;
  }
  mirrored_ = !mirrored_;
  run_steps(body, "'mirror'");
  mirrored_ = !mirrored_;
}

void ServoLowering::include_step(const YamlNode& value) {
  const LoadedFile* loaded = scopes_.load_include(
      value, "wave.yaml",
      [](const std::string&, const std::string& reason) { return "cannot include it: " + reason; },
      loader_, reporter_);
  if (loaded == nullptr) return;
  reporter_.push_include(value.location);
  run_file(*loaded, false);
  reporter_.pop_include();
}

void ServoLowering::section_step(const YamlNode& step, const YamlNode& value) {
  const YamlNode* section = scopes_.find_section(value, reporter_);
  if (section == nullptr) return;
  if (std::find(sections_running_.begin(), sections_running_.end(), section) !=
      sections_running_.end()) {
    reporter_.error(value.location, "section '" + value.scalar + "' performs itself");
    return;
  }
  YamlNode copy;
  std::optional<Reporter::Note> performance;
  const YamlNode* list = perform_section(step, value, *section, copy, performance);
  if (list == nullptr) return;
  timeline_.markers.push_back({now_, "section " + value.scalar, value.location});
  sections_running_.push_back(section);
  // A performance with values explains every mistake inside it; a plain one names itself
  // under the warnings (an error inside it is the section's own).
  if (performance) {
    reporter_.push_context(*performance);
  } else {
    reporter_.push_performance(value.location, value.scalar);
  }
  run_steps(*list, "section '" + value.scalar + "'");
  if (performance) {
    reporter_.pop_context();
  } else {
    reporter_.pop_performance();
  }
  sections_running_.pop_back();
}

const YamlNode* ServoLowering::perform_section(const YamlNode& step, const YamlNode& name,
                                               const YamlNode& section, YamlNode& copy,
                                               std::optional<Reporter::Note>& performance) {
  const std::string quoted = "section '" + name.scalar + "'";
  const Reporter::Note here{name.location, quoted + " is performed here"};
  const YamlNode* steps = &section;
  const YamlNode* params = nullptr;
  if (section.is_map()) {
    reporter_.check_keys(section, {"params", "steps"}, "in a section");
    params = section.find("params");
    steps = section.find("steps");
    if (steps == nullptr) {
      reporter_.error(section.location, quoted + " needs 'steps', the list of its steps");
      return nullptr;
    }
  }
  std::map<std::string, std::string, std::less<>> values;
  std::vector<std::string> names;  // in the order declared
  bool ok = true;
  if (params != nullptr && params->kind != YamlNode::Kind::Null) {
    if (!params->is_map()) {
      reporter_.error(params->location,
                      "'params' must be a map of parameter names to default values, e.g. "
                      "'params: {amount: 40}'");
      return nullptr;
    }
    for (const auto& [key, v] : params->entries) {
      if (!is_parameter_name(key.scalar)) {
        reporter_.error(key.location, "'" + key.scalar +
                                          "' cannot be a parameter name; use letters, digits "
                                          "and '_', starting with a letter");
        ok = false;
      } else if (!v.is_scalar()) {
        reporter_.error(v.location, "parameter '" + key.scalar +
                                        "' needs a default that is a single value, e.g. '" +
                                        key.scalar + ": 40'");
        ok = false;
      } else {
        values[key.scalar] = v.scalar;
        names.push_back(key.scalar);
      }
    }
  }
  if (const YamlNode* with = step.find("with")) {
    if (!with->is_map()) {
      reporter_.error(with->location,
                      "'with' gives the section's parameters values, e.g. 'with: {amount: 80}'",
                      here);
      return nullptr;
    }
    for (const auto& [key, v] : with->entries) {
      auto it = values.find(key.scalar);
      if (it == values.end()) {
        std::string message = quoted + " has no parameter '" + key.scalar + "'";
        const std::string suggestion = did_you_mean(key.scalar, names);
        if (!suggestion.empty()) {
          message += "; did you mean '" + suggestion + "'?";
        } else if (names.empty()) {
          message += "; it declares none (under 'params:')";
        }
        reporter_.error(key.location, message, here);
        ok = false;
      } else if (!v.is_scalar()) {
        reporter_.error(v.location,
                        "'" + key.scalar +
                            "' takes a single value, such as 80 or wrist_roll, "
                            "not " +
                            std::string(kind_name(v)),
                        here);
        ok = false;
      } else {
        it->second = v.scalar;
      }
    }
  }
  if (!ok) return nullptr;
  if (!values.empty()) {
    std::string given;
    for (const std::string& n : names) given += (given.empty() ? "" : ", ") + n + ": " + values[n];
    performance = Reporter::Note{name.location, quoted + " is performed here with " + given};
  }
  if (!mentions_parameter(*steps)) return steps;
  copy = *steps;
  std::vector<std::pair<Location, std::string>> unknown;
  put_in_parameters(copy, values, unknown);
  for (const auto& [at, word] : unknown) {
    std::string message = "unknown parameter '$" + word + "' in " + quoted;
    const std::string suggestion = did_you_mean(word, names);
    if (!suggestion.empty()) {
      message += "; did you mean '$" + suggestion + "'?";
    } else if (names.empty()) {
      message += ", which declares none; declare it under 'params:'";
    }
    reporter_.error(at, message, performance.value_or(here));
  }
  return unknown.empty() ? &copy : nullptr;
}

void ServoLowering::together_step(const YamlNode& step, const YamlNode& tracks) {
  if (!tracks.is_map() || tracks.entries.empty()) {
    reporter_.error(tracks.location,
                    "'together' takes named tracks, each a list of steps, e.g. "
                    "'together: {arm: [...], claw: [...]}'");
    return;
  }
  const ExactMs start = now_;
  ExactMs longest = start;
  std::uint64_t most_actions = 0;
  const std::uint64_t before = min_actions_;
  const std::size_t errors_before = reporter_.errors_reported();
  const bool known = std::any_of(pos_.begin(), pos_.end(), [](auto& p) { return p.has_value(); });
  Track* const outer = track_;
  blocks_.emplace_back();
  for (const auto& [name, list] : tracks.entries) {
    Track track{name.scalar, name.location, {}};
    track_ = &track;
    blocks_.back().track = &track;
    now_ = start;
    min_actions_ = before;
    run_steps(list, "track '" + name.scalar + "'");
    longest = std::max(longest, now_);
    most_actions = std::max(most_actions, min_actions_ - before);
  }
  blocks_.pop_back();
  track_ = outer;
  min_actions_ = before + most_actions;
  now_ = longest;
  // A track may wait (or start `at:` later) while another moves; but when nothing had a position
  // before the block, one track must move at its start, or the controller has nothing to send.
  if (known || track_ != nullptr || reporter_.errors_reported() > errors_before) return;
  std::optional<double> first;
  for (std::size_t s = 0; s < timeline_.servo_count(); ++s) {
    if (timeline_.count(s) == 0) continue;
    const double t = timeline_.start_of(s, 0).value();
    first = first ? std::min(*first, t) : t;
  }
  const double until = first.value_or(longest.value());
  if (until > start.value()) {
    reporter_.error(step.location,
                    "nothing to hold from the start of this 'together' until " +
                        format_seconds(static_cast<std::uint64_t>(std::llround(until))) +
                        ": no servo has a position yet and no track moves at the start; begin "
                        "one track with a move");
  }
}

bool ServoLowering::outside_tracks(const YamlNode& value, std::string_view verb) {
  if (blocks_.empty()) return true;
  const Track& track = *blocks_.front().track;
  reporter_.error(value.location,
                  "'" + std::string(verb) +
                      "' inside a 'together' track would change the other tracks' " +
                      (verb == "tempo" ? "beats" : "bars") +
                      " too; "
                      "move it out of the 'together', before or after it",
                  Reporter::Note{track.at, "in track '" + track.name + "' of this 'together'"});
  return false;
}

void ServoLowering::tempo_step(const YamlNode& value) {
  if (!outside_tracks(value, "tempo")) return;
  if (auto bpm = parse_tempo(value, reporter_)) {
    timeline_.tempo_map.set_tempo(now_, *bpm);
    timeline_.markers.push_back({now_, "tempo " + value.scalar, value.location});
  }
}

void ServoLowering::meter_step(const YamlNode& value) {
  if (!outside_tracks(value, "meter")) return;
  const std::optional<int> meter = parse_meter(value, reporter_);
  if (meter && change_meter(*meter, value.location, "'meter: " + value.scalar + "'")) {
    timeline_.markers.push_back({now_, "meter " + value.scalar, value.location});
  }
}

bool ServoLowering::change_meter(int beats_per_bar, Location at, std::string_view what) {
  TempoMap& map = timeline_.tempo_map;
  const int current = map.meter_at(now_);
  if (current > 0 && map.bpm_at(now_) > 0 && beats_per_bar != current) {
    const ExactMs bar = map.bar_at(now_);
    if (bar.den() != 1) {
      const std::int64_t whole = bar.num() / bar.den();  // bars are never negative
      const ExactMs into = map.beat_at(now_) - map.beat_of_bar(whole).value_or(ExactMs(0));
      reporter_.error(at, std::string(what) + " must fall on a bar line, but here it is " +
                              beats_text(into) + " into bar " + std::to_string(whole + 1) + " (" +
                              beats_text(ExactMs(current) - into) + " before bar " +
                              std::to_string(whole + 2) + ")");
      return false;
    }
  }
  map.set_meter(now_, beats_per_bar);
  return true;
}

void ServoLowering::tolerance_step(const YamlNode& value) {
  if (auto t = parse_tolerance(value)) lists_.back().tolerance = t;
}

ServoProgram lower_servo_program(const Robot& robot, const LoadedFile& main, FileLoader& loader,
                                 Reporter& reporter) {
  return ServoLowering(robot, loader, reporter).run(main);
}

}  // namespace seqc::compiler
