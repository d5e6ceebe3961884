#include "compiler/lang/servo_lowering.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <memory>

#include "compiler/lang/positions.hpp"
#include "compiler/lang/scope_chain.hpp"
#include "compiler/lang/step_parts.hpp"
#include "compiler/lang/units.hpp"
#include "runtime/protocol/group_download.hpp"

namespace seqc::compiler {
namespace {

constexpr std::uint64_t kMaxGroupMs = std::uint64_t{lsc::kMaxActionMs} * lsc::kMaxActions;

std::uint64_t saturating_add(std::uint64_t a, std::uint64_t b) {
  return a > std::numeric_limits<std::uint64_t>::max() - b
             ? std::numeric_limits<std::uint64_t>::max()
             : a + b;
}
std::uint64_t saturating_mul(std::uint64_t a, std::uint64_t b) {
  if (a != 0 && b > std::numeric_limits<std::uint64_t>::max() / a) {
    return std::numeric_limits<std::uint64_t>::max();
  }
  return a * b;
}

class ServoLowering {
 public:
  ServoLowering(const Robot& robot, FileLoader& loader, Reporter& reporter)
      : robot_(robot),
        loader_(loader),
        reporter_(reporter),
        scopes_(robot.home_servos),
        pos_(robot.info.servos.size()) {}

  ServoProgram run(const LoadedFile& main) {
    run_file(main, true);
    if (actions_ > lsc::kMaxActions) {
      const std::vector<Location> sites = reporter_.include_sites();
      reporter_.set_include_sites(overflow_sites_);
      reporter_.error(overflow_at_,
                      "the sequence needs " + std::to_string(actions_) + "/" +
                          std::to_string(lsc::kMaxActions) +
                          " actions; a group holds at most 1,020 (4 blocks of 255), and this "
                          "step makes action 1,021");
      reporter_.set_include_sites(sites);
    } else if (actions_ == 0 && sequence_at_ && reporter_.errors_reported() == 0) {
      reporter_.error(*sequence_at_, "the sequence makes no actions; a group needs at least one");
    }
    ServoProgram program;
    program.robot = robot_.info;
    program.keyframes = std::move(keyframes_);
    return program;
  }

 private:
  // ---- files and scopes ---------------------------------------------------------------------

  void run_file(const LoadedFile& f, bool is_main) {
    const YamlNode* map = file_root(f, reporter_);
    if (map == nullptr) return;
    const YamlNode& root = *map;
    reporter_.check_keys(
        root, {"robot", "tempo", "resolution", "poses", "sequence", "name", "description"},
        "at the top level");
    if (!is_main && !check_included_robot(root, robot_.info.profile, reporter_)) {
      return;  // its steps would only add errors about servos this robot lacks
    }
    FileScope& scope = scope_for(f);
    const YamlNode* sequence = find_sequence(root, reporter_);
    if (sequence == nullptr) return;
    if (is_main) sequence_at_ = sequence->location;
    scopes_.push(scope);
    run_steps(*sequence, "'sequence'");
    scopes_.pop();
  }

  FileScope& scope_for(const LoadedFile& f) {
    auto [scope, fresh] = scopes_.open(f, reporter_);
    if (!fresh) return scope;
    const YamlNode& root = *f.root;
    if (const YamlNode* p = root.find("poses")) parse_poses(*p, scope);
    if (const YamlNode* r = root.find("resolution")) {
      scopes_.push(scope);  // so beats use this file's tempo
      auto ms = time_ms(*r, "'resolution'");
      scopes_.pop();
      if (ms && *ms < lsc::kMinActionMs) {
        reporter_.error(r->location, "resolution " + std::to_string(*ms) +
                                         "ms is below the controller's minimum of 20ms per "
                                         "action");
      } else if (ms) {
        scope.resolution_ms = *ms;
      }
    }
    return scope;
  }

  void parse_poses(const YamlNode& poses, FileScope& scope) {
    compiler::parse_poses(
        poses, scope, "'poses' must be a map of pose names to servo positions",
        "servo: position, e.g. {claw: 500}",
        [this](const YamlNode& map, const std::string& where) {
          std::vector<PositionEntry> entries = parse_positions(map, where);
          for (const PositionEntry& e : entries) {
            if (!e.value.relative)
              check_limits(e, e.output, absolute_units(e, e.output, false), {});
          }
          return entries;
        },
        reporter_);
  }

  // ---- values -------------------------------------------------------------------------------

  ScopeChain::ParseEntries entries_parser() {
    return [this](const YamlNode& map, const std::string& where) {
      return parse_positions(map, where);
    };
  }

  std::vector<PositionEntry> parse_positions(const YamlNode& map, const std::string& where) {
    std::vector<PositionEntry> out;
    out.reserve(map.entries.size());
    std::vector<bool> given(robot_.info.servos.size());
    for (const auto& [key, value] : map.entries) {
      auto it = robot_.names.find(key.scalar);
      if (it == robot_.names.end()) {
        reporter_.unknown(key.location, "servo", key.scalar, robot_.name_list(), where);
        continue;
      }
      auto e = parse_position_entry(key, value, it->second, "500, 90deg, +50", reporter_);
      if (!e) continue;
      if (given[e->output]) {
        reporter_.error(key.location, "servo '" + robot_.info.servos[e->output].name +
                                          "' is given twice " + where);
        continue;
      }
      given[e->output] = true;
      out.push_back(std::move(*e));
    }
    return out;
  }

  // The absolute position of an absolute entry, in device units, on servo `target`.
  double absolute_units(const PositionEntry& e, std::size_t target, bool reflect) const {
    const ServoInfo& dst = robot_.info.servos[target];
    if (e.home) return dst.home;
    double v = e.value.degrees ? robot_.degrees_to_units(e.value.amount, false) : e.value.amount;
    if (reflect) v = dst.home - (v - robot_.info.servos[e.output].home);
    return v;
  }

  // Reports a position outside the servo's limits; `how` explains where the value came from.
  bool check_limits(const PositionEntry& e, std::size_t target, double units, std::string how,
                    std::optional<Reporter::Note> note = {}) {
    const ServoInfo& s = robot_.info.servos[target];
    return check_position_limits(e, s.name, s.min, s.max, units, std::move(how), std::move(note),
                                 reporter_);
  }

  std::optional<std::uint32_t> time_ms(const YamlNode& node, std::string_view what) {
    return scopes_.time_ms(node, what, kMaxGroupMs,
                           "is longer than a whole group can last (1,020 actions of 30s)",
                           reporter_);
  }

  // ---- steps --------------------------------------------------------------------------------

  void run_steps(const YamlNode& list, std::string_view what) {
    for (const YamlNode& step : step_items(list, what, reporter_)) run_step(step);
  }

  void run_step(const YamlNode& step) {
    static constexpr std::string_view kVerbs[] = {"move", "wait", "repeat", "include", "mirror"};
    if (!step.is_map()) {
      reporter_.error(step.location,
                      "a step must be a map such as 'move: home' or 'wait: 1s', not " +
                          std::string(kind_name(step)));
      return;
    }
    const YamlNode* verb_key = nullptr;
    const YamlNode* verb_value = nullptr;
    for (const auto& [key, value] : step.entries) {
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
              step, {"move", "wait", "repeat", "include", "mirror", "time", "ease", "steps", "do"},
              "in a step")) {
        reporter_.error(step.location, "a step needs one of: move, wait, repeat, include, mirror");
      }
      return;
    }
    const std::string& verb = verb_key->scalar;
    if (verb == "move") {
      if (reporter_.check_keys(step, {"move", "time", "ease", "steps"}, "in a move step")) {
        move_step(step, *verb_value);
      }
    } else if (verb == "wait") {
      if (reporter_.check_keys(step, {"wait"}, "in a wait step")) wait_step(step, *verb_value);
    } else if (verb == "repeat") {
      if (reporter_.check_keys(step, {"repeat", "do"}, "in a repeat step")) {
        repeat_step(step, *verb_value);
      }
    } else if (verb == "include") {
      if (reporter_.check_keys(step, {"include"}, "in an include step")) {
        include_step(step, *verb_value);
      }
    } else if (reporter_.check_keys(step, {"mirror"}, "in a mirror step")) {
      mirror_step(step, *verb_value);
    }
  }

  void move_step(const YamlNode& step, const YamlNode& target) {
    std::vector<PositionEntry> inline_entries;
    std::optional<Reporter::Note> note;
    const std::vector<PositionEntry>* entries =
        scopes_.move_entries(target, "servo", entries_parser(), inline_entries, note, reporter_);
    if (entries == nullptr) return;

    const YamlNode* time_node = step.find("time");
    std::optional<std::uint32_t> total;
    if (time_node == nullptr) {
      reporter_.error(step.location, "this move needs a 'time', e.g. 'time: 500ms'");
    } else {
      total = time_ms(*time_node, "'time'");
    }

    Ease ease = Ease::Linear;
    bool eased = false;
    if (const YamlNode* e = step.find("ease")) {
      auto parsed = parse_ease(*e, reporter_);
      if (!parsed) return;
      ease = *parsed;
      eased = ease != Ease::Linear;
    }
    std::optional<long long> steps;
    const YamlNode* steps_node = step.find("steps");
    if (steps_node != nullptr) {
      steps = parse_integer(*steps_node, 1, lsc::kMaxActions, "'steps'", reporter_);
      if (!steps) return;
    }

    // Resolve every target before checking time, so one run reports both kinds of mistake.
    // targets[servo]: the position to reach; a later entry for the same servo (possible after
    // mirroring) replaces an earlier one. Walked in servo order below.
    std::vector<std::optional<int>>& targets = scratch_targets_;
    targets.assign(pos_.size(), std::nullopt);
    std::size_t target_count = 0;
    bool ok = true;
    for (const PositionEntry& e : *entries) {
      const bool reflect = mirrored_ && robot_.mirror.count(e.output) != 0;
      const std::size_t servo = reflect ? robot_.mirror.at(e.output) : e.output;
      std::string how;
      double units = 0;
      if (e.value.relative) {
        double delta =
            e.value.degrees ? robot_.degrees_to_units(e.value.amount, true) : e.value.amount;
        if (reflect) delta = -delta;
        auto reached = relative_units(e, robot_.info.servos[servo].name, pos_[servo], delta, how,
                                      note, reporter_);
        if (!reached) {
          ok = false;
          continue;
        }
        units = *reached;
      } else {
        units = absolute_units(e, servo, reflect);
      }
      if (reflect) {
        how += std::string(how.empty() ? "" : ", ") + "mirrored from '" +
               robot_.info.servos[e.output].name + "'";
      }
      if (!check_limits(e, servo, units, how, note)) {
        ok = false;
        continue;
      }
      if (!targets[servo]) ++target_count;
      targets[servo] = static_cast<int>(std::llround(units));
    }
    if (!ok || !total) return;

    const std::uint32_t t = *total;
    if (t < lsc::kMinActionMs) {
      reporter_.error(time_node->location, "time " + std::to_string(t) +
                                               "ms is below the controller's minimum of 20ms per "
                                               "action");
      return;
    }
    std::uint64_t n = 1;
    if (steps) {
      n = static_cast<std::uint64_t>(*steps);
    } else if (eased) {
      const std::uint32_t res = scopes_.resolution_ms().value_or(kDefaultResolutionMs);
      n = std::max<std::uint64_t>(1, t / res);
    }
    n = std::max<std::uint64_t>(n, (t + lsc::kMaxActionMs - 1) / lsc::kMaxActionMs);
    if (t / n < lsc::kMinActionMs) {
      reporter_.error(steps_node != nullptr ? steps_node->location : time_node->location,
                      std::to_string(n) + " steps of " +
                          format_ms(static_cast<double>(t) / static_cast<double>(n)) +
                          " are shorter than the controller's 20ms minimum per action; use at "
                          "most " +
                          std::to_string(t / lsc::kMinActionMs) + " steps");
      return;
    }
    if (n > 1) {
      for (std::size_t servo = 0; servo < targets.size(); ++servo) {
        if (!targets[servo] || pos_[servo]) continue;
        reporter_.error(step.location, "'" + robot_.info.servos[servo].name +
                                           "' has no known position before this move, so it "
                                           "cannot be split into " +
                                           std::to_string(n) +
                                           " actions; move it to an absolute position first");
        return;
      }
    }

    // Where each target servo starts (all are known when the move is split, checked above).
    std::vector<std::optional<int>> start;
    if (n > 1) start = pos_;
    struct Fastest {
      double speed = 0;
      int delta = 0;
      std::uint32_t ms = 0;
    };
    std::map<std::size_t, Fastest> fastest;
    std::uint64_t done_ms = 0;
    for (std::uint64_t k = 1; k <= n; ++k) {
      const std::uint64_t until = (t * k + n / 2) / n;
      const auto piece = static_cast<std::uint16_t>(until - done_ms);
      done_ms = until;
      std::vector<lsc::ServoTarget> out;
      out.reserve(target_count);
      for (std::size_t servo = 0; servo < targets.size(); ++servo) {
        if (!targets[servo]) continue;
        const int end = *targets[servo];
        int p = end;
        if (k < n) {
          const double s = start[servo].value();
          const double f = ease_at(ease, static_cast<double>(k) / static_cast<double>(n));
          p = static_cast<int>(std::llround(s + (end - s) * f));
        }
        const ServoInfo& info = robot_.info.servos[servo];
        if (info.max_speed && pos_[servo]) {
          const int delta = std::abs(p - *pos_[servo]);
          const double speed = delta * 1000.0 / piece;
          if (speed > *info.max_speed && speed > fastest[servo].speed) {
            fastest[servo] = {speed, delta, piece};
          }
        }
        pos_[servo] = p;
        out.push_back({info.id, static_cast<std::uint16_t>(p)});
      }
      emit(step.location, piece, std::move(out));
      if (actions_ > lsc::kMaxActions) {  // the rest only counts
        actions_ = saturating_add(actions_, n - k);
        break;
      }
    }
    for (const auto& [servo, f] : fastest) {
      const ServoInfo& info = robot_.info.servos[servo];
      reporter_.warning(step.location,
                        "'" + info.name + "' moves " + std::to_string(f.delta) + " in " +
                            std::to_string(f.ms) + "ms (" + std::to_string(std::llround(f.speed)) +
                            "/s), faster than its " + "max_speed " +
                            std::to_string(std::llround(*info.max_speed)) + "/s",
                        note);
    }
  }

  void wait_step(const YamlNode& step, const YamlNode& value) {
    auto total = time_ms(value, "'wait'");
    if (!total) return;
    const std::uint32_t t = *total;
    if (t < lsc::kMinActionMs) {
      reporter_.error(value.location, "wait of " + std::to_string(t) +
                                          "ms is below the controller's minimum of 20ms per "
                                          "action");
      return;
    }
    std::vector<lsc::ServoTarget> held;
    for (std::size_t i = 0; i < pos_.size(); ++i) {
      if (pos_[i]) {
        held.push_back({robot_.info.servos[i].id, static_cast<std::uint16_t>(*pos_[i])});
      }
    }
    if (held.empty()) {
      reporter_.error(step.location,
                      "nothing to hold: no servo has a position yet (a controller action carries "
                      "positions); move first, then wait");
      return;
    }
    const std::uint64_t n = (t + lsc::kMaxActionMs - 1) / lsc::kMaxActionMs;
    std::uint64_t done_ms = 0;
    for (std::uint64_t k = 1; k <= n; ++k) {
      const std::uint64_t until = (t * k + n / 2) / n;
      emit(step.location, static_cast<std::uint16_t>(until - done_ms), held);
      done_ms = until;
      if (actions_ > lsc::kMaxActions) {
        actions_ = saturating_add(actions_, n - k);
        break;
      }
    }
  }

  void repeat_step(const YamlNode& step, const YamlNode& value) {
    const auto repeat = parse_repeat(step, value, reporter_);
    if (!repeat) return;
    std::uint64_t per_pass = 0;
    for (long long i = 0; i < repeat->times; ++i) {
      if (i > 0 && actions_ > lsc::kMaxActions) {  // already too long: count, do not expand
        actions_ = saturating_add(
            actions_, saturating_mul(static_cast<std::uint64_t>(repeat->times - i), per_pass));
        break;
      }
      const std::uint64_t before = actions_;
      run_steps(*repeat->body, "'do'");
      per_pass = actions_ - before;
    }
  }

  void mirror_step(const YamlNode& step, const YamlNode& body) {
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

  void include_step(const YamlNode& step, const YamlNode& value) {
    (void)step;
    const LoadedFile* loaded = scopes_.load_include(
        value, "wave.yaml",
        [](const std::string&, const std::string& reason) {
          return "cannot include it: " + reason;
        },
        loader_, reporter_);
    if (loaded == nullptr) return;
    reporter_.push_include(value.location);
    run_file(*loaded, false);
    reporter_.pop_include();
  }

  void emit(Location at, std::uint16_t time, std::vector<lsc::ServoTarget> targets) {
    ++actions_;
    if (actions_ == lsc::kMaxActions + 1) {
      overflow_at_ = at;
      overflow_sites_ = reporter_.include_sites();
    }
    if (actions_ <= lsc::kMaxActions) {
      keyframes_.push_back({static_cast<std::uint32_t>(now_ms_), time, std::move(targets), at});
      now_ms_ += time;
    }
  }

  const Robot& robot_;
  FileLoader& loader_;
  Reporter& reporter_;
  ScopeChain scopes_;
  std::vector<std::optional<int>> pos_;
  std::vector<std::optional<int>> scratch_targets_;  // move_step's, kept to reuse its memory
  bool mirrored_ = false;
  std::uint64_t actions_ = 0;
  std::uint64_t now_ms_ = 0;
  Location overflow_at_;
  std::vector<Location> overflow_sites_;
  std::optional<Location> sequence_at_;
  std::vector<Keyframe> keyframes_;
};

}  // namespace

ServoProgram lower_servo_program(const Robot& robot, const LoadedFile& main, FileLoader& loader,
                                 Reporter& reporter) {
  return ServoLowering(robot, loader, reporter).run(main);
}

}  // namespace seqc::compiler
