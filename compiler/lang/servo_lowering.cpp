// The servo-controller front end: files, step lists and the structural steps. Motion steps
// (move, wait, through) are in servo_motion.cpp; fitting the finished timeline into actions is
// compiler/fitting/.
#include "compiler/lang/servo_lowering.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

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
  if (is_main) {
    sequence_at_ = sequence->location;
    timeline_.tempo = scope.tempo.value_or(0);
    timeline_.beats_per_bar = scope.beats_per_bar.value_or(0);
  }
  scopes_.push(scope);
  run_steps(*sequence, "'sequence'");
  scopes_.pop();
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
  lists_.push_back({now_, std::nullopt, std::nullopt});
  for (const YamlNode& step : step_items(list, what, reporter_)) run_step(step);
  lists_.pop_back();
}

void ServoLowering::run_step(const YamlNode& step) {
  static constexpr std::string_view kVerbs[] = {"move",    "wait",     "through", "repeat",
                                                "include", "mirror",   "section", "together",
                                                "tempo",   "tolerance"};
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
             "tempo", "tolerance", "time", "ease", "steps", "do", "at"},
            "in a step")) {
      reporter_.error(step.location,
                      "a step needs one of: move, wait, through, repeat, include, mirror, "
                      "section, together, tempo, tolerance");
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
    if (reporter_.check_keys(step, {"section", "at"}, "in a section step") && apply_at(step)) {
      section_step(*verb_value);
    }
  } else if (verb == "together") {
    if (reporter_.check_keys(step, {"together", "at"}, "in a together step") && apply_at(step)) {
      together_step(step, *verb_value);
    }
  } else if (verb == "tempo") {
    if (reporter_.check_keys(step, {"tempo"}, "in a tempo step")) tempo_step(*verb_value);
  } else {
    tolerance_step(*verb_value);
  }
}

bool ServoLowering::apply_at(const YamlNode& step) {
  const YamlNode* at = step.find("at");
  if (at == nullptr) return true;
  const std::optional<double> tempo = lists_.back().tempo;
  auto offset = scopes_.exact_ms(*at, "'at'", tempo, reporter_);
  if (!offset) return false;
  const ExactMs target = lists_.back().start + *offset;
  if (target < now_) {
    reporter_.error(
        at->location,
        "'at: " + at->scalar + "' is " + format_exact_ms(now_ - target) +
            " in the past: the steps before it already run until " +
            format_seconds(static_cast<std::uint64_t>((now_ - lists_.back().start).round())) +
            " of this list");
    return false;
  }
  if (target > now_) {
    const bool known = std::any_of(pos_.begin(), pos_.end(), [](auto& p) { return p.has_value(); });
    if (!known) {
      reporter_.error(at->location,
                      "nothing to hold until 'at': no servo has a position yet; start with a "
                      "move");
      return false;
    }
    timeline_.markers.push_back({target, "at " + at->scalar, at->location});
    count_actions((target - now_).value() > 30000 ? 2 : 1, at->location);
    now_ = target;
  }
  return true;
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

void ServoLowering::section_step(const YamlNode& value) {
  const YamlNode* list = scopes_.find_section(value, reporter_);
  if (list == nullptr) return;
  if (std::find(sections_running_.begin(), sections_running_.end(), list) !=
      sections_running_.end()) {
    reporter_.error(value.location, "section '" + value.scalar + "' performs itself");
    return;
  }
  timeline_.markers.push_back({now_, "section " + value.scalar, value.location});
  sections_running_.push_back(list);
  reporter_.push_performance(value.location, value.scalar);
  run_steps(*list, "section '" + value.scalar + "'");
  reporter_.pop_performance();
  sections_running_.pop_back();
}

void ServoLowering::together_step(const YamlNode& step, const YamlNode& tracks) {
  if (!tracks.is_map() || tracks.entries.empty()) {
    reporter_.error(tracks.location,
                    "'together' takes named tracks, each a list of steps, e.g. "
                    "'together: {arm: [...], claw: [...]}'");
    return;
  }
  if (track_ != nullptr) {
    reporter_.error(step.location, "'together' cannot be used inside a track of another");
    return;
  }
  const ExactMs start = now_;
  ExactMs longest = start;
  std::uint64_t most_actions = 0;
  const std::uint64_t before = min_actions_;
  claimed_.clear();
  for (const auto& [name, list] : tracks.entries) {
    Track track{name.scalar, name.location, {}};
    track_ = &track;
    now_ = start;
    min_actions_ = before;
    run_steps(list, "track '" + name.scalar + "'");
    longest = std::max(longest, now_);
    most_actions = std::max(most_actions, min_actions_ - before);
  }
  track_ = nullptr;
  claimed_.clear();
  min_actions_ = before + most_actions;
  now_ = longest;
}

void ServoLowering::tempo_step(const YamlNode& value) {
  if (auto bpm = parse_tempo(value, reporter_)) {
    lists_.back().tempo = bpm;
    timeline_.markers.push_back({now_, "tempo " + value.scalar, value.location});
  }
}

void ServoLowering::tolerance_step(const YamlNode& value) {
  if (auto t = parse_tolerance(value)) lists_.back().tolerance = t;
}

ServoProgram lower_servo_program(const Robot& robot, const LoadedFile& main, FileLoader& loader,
                                 Reporter& reporter) {
  return ServoLowering(robot, loader, reporter).run(main);
}

}  // namespace seqc::compiler
