#include "compiler/lang/servo_lowering.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <memory>

#include "compiler/lang/units.hpp"
#include "runtime/protocol/group_download.hpp"

namespace seqc::compiler {
namespace {

constexpr std::uint64_t kMaxGroupMs = std::uint64_t{lsc::kMaxActionMs} * lsc::kMaxActions;

enum class Ease { Linear, In, Out, InOut };

// Quadratic easing: gentle enough for servos, and simple to reason about in a listing.
double ease_at(Ease ease, double t) {
  switch (ease) {
    case Ease::Linear:
      return t;
    case Ease::In:
      return t * t;
    case Ease::Out:
      return 1 - (1 - t) * (1 - t);
    case Ease::InOut:
      return t < 0.5 ? 2 * t * t : 1 - 2 * (1 - t) * (1 - t);
  }
  return t;
}

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

std::string ms_text(double ms) {
  if (ms == std::floor(ms)) return std::to_string(static_cast<long long>(ms)) + "ms";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1fms", ms);
  return buf;
}

struct PoseEntry {
  std::size_t servo = 0;
  std::string written;  // as in the file, for messages
  bool home = false;    // the keyword `home`
  PositionValue value;
  Location at;
};

struct Pose {
  std::vector<PoseEntry> entries;
  Location at;
};

// What a file contributes while its steps run: its poses and its tempo/resolution.
struct FileScope {
  const LoadedFile* file = nullptr;
  std::map<std::string, Pose, std::less<>> poses;
  std::optional<double> tempo;
  std::optional<std::uint32_t> resolution_ms;
};

class ServoLowering {
 public:
  ServoLowering(const Robot& robot, FileLoader& loader, Reporter& reporter)
      : robot_(robot), loader_(loader), reporter_(reporter), pos_(robot.info.servos.size()) {}

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
    if (!f.root) return;
    const YamlNode& root = *f.root;
    if (!root.is_map()) {
      reporter_.error(root.location,
                      "a choreography file must be a map with 'robot' and 'sequence' keys");
      return;
    }
    reporter_.check_keys(
        root, {"robot", "tempo", "resolution", "poses", "sequence", "name", "description"},
        "at the top level");
    if (!is_main) {
      if (const YamlNode* r = root.find("robot")) {
        auto name = included_robot_name(*r, reporter_);
        if (name && *name != robot_.info.profile) {
          reporter_.error(r->location, "this file is for robot '" + *name +
                                           "' but is included by a file for '" +
                                           robot_.info.profile + "'");
          return;  // its steps would only add errors about servos this robot lacks
        }
      }
    }
    FileScope& scope = scope_for(f);
    const YamlNode* sequence = root.find("sequence");
    if (sequence == nullptr) {
      reporter_.error(root.location, "missing 'sequence': the list of steps to perform");
      return;
    }
    if (is_main) sequence_at_ = sequence->location;
    chain_.push_back(&scope);
    run_steps(*sequence, "'sequence'");
    chain_.pop_back();
  }

  FileScope& scope_for(const LoadedFile& f) {
    auto it = scopes_.find(f.path);
    if (it != scopes_.end()) return *it->second;
    auto scope = std::make_unique<FileScope>();
    scope->file = &f;
    const YamlNode& root = *f.root;
    if (const YamlNode* t = root.find("tempo")) scope->tempo = parse_tempo(*t);
    if (const YamlNode* p = root.find("poses")) parse_poses(*p, *scope);
    FileScope& ref = *scope;
    scopes_.emplace(f.path, std::move(scope));
    if (const YamlNode* r = root.find("resolution")) {
      chain_.push_back(&ref);  // so beats use this file's tempo
      auto ms = time_ms(*r, "'resolution'");
      chain_.pop_back();
      if (ms && *ms < lsc::kMinActionMs) {
        reporter_.error(r->location, "resolution " + std::to_string(*ms) +
                                         "ms is below the controller's minimum of 20ms per "
                                         "action");
      } else if (ms) {
        ref.resolution_ms = *ms;
      }
    }
    return ref;
  }

  std::optional<double> parse_tempo(const YamlNode& node) {
    std::string_view text = node.is_scalar() ? std::string_view(node.scalar) : "";
    if (text.size() > 3 && text.substr(text.size() - 3) == "bpm") text.remove_suffix(3);
    double bpm = 0;
    if (!node.is_scalar() || !parse_decimal(text, bpm) || bpm < 1 || bpm > 1000) {
      reporter_.error(node.location,
                      "'tempo' must be beats per minute between 1 and 1000, e.g. 'tempo: 120'");
      return std::nullopt;
    }
    return bpm;
  }

  void parse_poses(const YamlNode& poses, FileScope& scope) {
    if (poses.kind == YamlNode::Kind::Null) return;
    if (!poses.is_map()) {
      reporter_.error(poses.location, "'poses' must be a map of pose names to servo positions");
      return;
    }
    for (const auto& [key, value] : poses.entries) {
      Pose pose;
      pose.at = key.location;
      if (!value.is_map()) {
        reporter_.error(value.location, "pose '" + key.scalar +
                                            "' must be a map of servo: position, e.g. "
                                            "{claw: 500}");
      } else {
        pose.entries = parse_positions(value, "in pose '" + key.scalar + "'");
        for (const PoseEntry& e : pose.entries) {
          if (!e.value.relative) check_limits(e, e.servo, absolute_units(e, e.servo, false), {});
        }
      }
      scope.poses.emplace(key.scalar, std::move(pose));
    }
  }

  // ---- values -------------------------------------------------------------------------------

  std::vector<PoseEntry> parse_positions(const YamlNode& map, const std::string& where) {
    std::vector<PoseEntry> out;
    out.reserve(map.entries.size());
    std::vector<bool> given(robot_.info.servos.size());
    for (const auto& [key, value] : map.entries) {
      auto it = robot_.names.find(key.scalar);
      if (it == robot_.names.end()) {
        reporter_.unknown(key.location, "servo", key.scalar, robot_.name_list(), where);
        continue;
      }
      PoseEntry e;
      e.servo = it->second;
      e.at = value.location;
      if (!value.is_scalar()) {
        reporter_.error(value.location, "the position of '" + key.scalar +
                                            "' must be a value such as 500, 90deg, +50 or home");
        continue;
      }
      e.written = value.scalar;
      if (value.scalar == "home") {
        e.home = true;
      } else if (auto p = parse_position(value.scalar); !p) {
        reporter_.error(value.location, p.error().message);
        continue;
      } else {
        e.value = *p;
      }
      if (given[e.servo]) {
        reporter_.error(key.location,
                        "servo '" + robot_.info.servos[e.servo].name + "' is given twice " + where);
        continue;
      }
      given[e.servo] = true;
      out.push_back(std::move(e));
    }
    return out;
  }

  // The absolute position of an absolute entry, in device units, on servo `target`.
  double absolute_units(const PoseEntry& e, std::size_t target, bool reflect) const {
    const ServoInfo& dst = robot_.info.servos[target];
    if (e.home) return dst.home;
    double v = e.value.degrees ? robot_.degrees_to_units(e.value.amount, false) : e.value.amount;
    if (reflect) v = dst.home - (v - robot_.info.servos[e.servo].home);
    return v;
  }

  // Reports a position outside the servo's limits; `how` explains where the value came from.
  bool check_limits(const PoseEntry& e, std::size_t target, double units, std::string how,
                    std::optional<Reporter::Note> note = {}) {
    const ServoInfo& s = robot_.info.servos[target];
    const long long p = std::llround(units);
    if (p >= s.min && p <= s.max) return true;
    if (how.empty() && e.value.degrees) how = e.written;
    std::string message = "'" + s.name + "' would move to " + std::to_string(p);
    if (!how.empty()) message += " (" + how + ")";
    message += p > s.max ? ", above its max " + std::to_string(s.max)
                         : ", below its min " + std::to_string(s.min);
    reporter_.error(e.at, std::move(message), std::move(note));
    return false;
  }

  std::optional<std::uint32_t> time_ms(const YamlNode& node, std::string_view what) {
    if (!node.is_scalar()) {
      reporter_.error(node.location,
                      std::string(what) + " must be a time such as 500ms, 1.5s or 2b");
      return std::nullopt;
    }
    auto t = parse_time(node.scalar);
    if (!t) {
      reporter_.error(node.location, t.error().message);
      return std::nullopt;
    }
    double ms = t->amount;
    if (t->unit == TimeUnit::Seconds) ms *= 1000;
    if (t->unit == TimeUnit::Beats) {
      std::optional<double> tempo;
      for (auto it = chain_.rbegin(); it != chain_.rend() && !tempo; ++it) tempo = (*it)->tempo;
      if (!tempo) {
        reporter_.error(node.location, "'" + node.scalar +
                                           "' counts beats but no 'tempo' is set; add e.g. "
                                           "'tempo: 120' at the top of the file");
        return std::nullopt;
      }
      ms *= 60000.0 / *tempo;
    }
    if (ms > static_cast<double>(kMaxGroupMs)) {
      reporter_.error(node.location, "'" + node.scalar +
                                         "' is longer than a whole group can last (1,020 actions "
                                         "of 30s)");
      return std::nullopt;
    }
    return static_cast<std::uint32_t>(std::llround(ms));
  }

  // ---- steps --------------------------------------------------------------------------------

  void run_steps(const YamlNode& list, std::string_view what) {
    if (list.kind == YamlNode::Kind::Null) return;
    if (!list.is_sequence()) {
      reporter_.error(list.location, std::string(what) +
                                         " must be a list of steps (each line "
                                         "starting with '- '), not " +
                                         std::string(kind_name(list)));
      return;
    }
    for (const YamlNode& step : list.items) run_step(step);
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

  const Pose* find_pose(const YamlNode& name) {
    for (auto it = chain_.rbegin(); it != chain_.rend(); ++it) {
      auto p = (*it)->poses.find(name.scalar);
      if (p != (*it)->poses.end()) return &p->second;
    }
    if (name.scalar == "home") return &builtin_home();
    std::vector<std::string> names{"home"};
    for (const FileScope* s : chain_) {
      for (const auto& [n, pose] : s->poses) names.push_back(n);
    }
    reporter_.unknown(name.location, "pose", name.scalar, names);
    return nullptr;
  }

  const Pose& builtin_home() {
    if (!home_) {
      home_ = std::make_unique<Pose>();
      for (std::size_t i : robot_.home_servos) {
        PoseEntry e;
        e.servo = i;
        e.home = true;
        e.written = "home";
        home_->entries.push_back(e);
      }
    }
    return *home_;
  }

  void move_step(const YamlNode& step, const YamlNode& target) {
    std::vector<PoseEntry> inline_entries;
    const std::vector<PoseEntry>* entries = nullptr;
    std::optional<Reporter::Note> note;
    if (target.is_scalar()) {
      const Pose* pose = find_pose(target);
      if (pose == nullptr) return;
      entries = &pose->entries;
      if (pose != home_.get())
        note = Reporter::Note{target.location, "in this move to pose '" + target.scalar + "'"};
    } else if (target.is_map()) {
      inline_entries = parse_positions(target, "in this move");
      entries = &inline_entries;
    } else {
      reporter_.error(target.location,
                      "'move' takes a pose name or a map of servo: position, not " +
                          std::string(kind_name(target)));
      return;
    }

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
      static const std::map<std::string, Ease, std::less<>> kEases = {
          {"linear", Ease::Linear},     {"in", Ease::In},      {"out", Ease::Out},
          {"in-out", Ease::InOut},      {"ease-in", Ease::In}, {"ease-out", Ease::Out},
          {"ease-in-out", Ease::InOut},
      };
      auto it = e->is_scalar() ? kEases.find(e->scalar) : kEases.end();
      if (it == kEases.end()) {
        reporter_.unknown(e->location, "easing", e->is_scalar() ? e->scalar : "",
                          {"linear", "in", "out", "in-out"});
        return;
      }
      ease = it->second;
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
    for (const PoseEntry& e : *entries) {
      const bool reflect = mirrored_ && robot_.mirror.count(e.servo) != 0;
      const std::size_t servo = reflect ? robot_.mirror.at(e.servo) : e.servo;
      std::string how;
      double units = 0;
      if (e.value.relative) {
        double delta =
            e.value.degrees ? robot_.degrees_to_units(e.value.amount, true) : e.value.amount;
        if (reflect) delta = -delta;
        const std::optional<int>& base = pos_[servo];
        if (!base) {
          reporter_.error(e.at,
                          "'" + robot_.info.servos[servo].name +
                              "' has no known position yet, so the relative move '" + e.written +
                              "' has nothing to add to; move it to an absolute position first",
                          note);
          ok = false;
          continue;
        }
        const long long d = std::llround(delta);
        units = static_cast<double>(*base + d);
        how = std::to_string(*base) + (d < 0 ? " " : " +") + std::to_string(d);
      } else {
        units = absolute_units(e, servo, reflect);
      }
      if (reflect) {
        how += std::string(how.empty() ? "" : ", ") + "mirrored from '" +
               robot_.info.servos[e.servo].name + "'";
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
      std::uint32_t res = kDefaultResolutionMs;
      for (auto it = chain_.rbegin(); it != chain_.rend(); ++it) {
        if ((*it)->resolution_ms) {
          res = *(*it)->resolution_ms;
          break;
        }
      }
      n = std::max<std::uint64_t>(1, t / res);
    }
    n = std::max<std::uint64_t>(n, (t + lsc::kMaxActionMs - 1) / lsc::kMaxActionMs);
    if (t / n < lsc::kMinActionMs) {
      reporter_.error(steps_node != nullptr ? steps_node->location : time_node->location,
                      std::to_string(n) + " steps of " +
                          ms_text(static_cast<double>(t) / static_cast<double>(n)) +
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
    auto times = parse_integer(value, 1, 65535, "the repeat count", reporter_);
    const YamlNode* body = step.find("do");
    if (body == nullptr) {
      reporter_.error(step.location, "'repeat' needs a 'do' list of the steps to repeat");
      return;
    }
    if (!times) return;
    std::uint64_t per_pass = 0;
    for (long long i = 0; i < *times; ++i) {
      if (i > 0 && actions_ > lsc::kMaxActions) {  // already too long: count, do not expand
        actions_ = saturating_add(actions_,
                                  saturating_mul(static_cast<std::uint64_t>(*times - i), per_pass));
        break;
      }
      const std::uint64_t before = actions_;
      run_steps(*body, "'do'");
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
    if (!value.is_scalar() || value.scalar.empty()) {
      reporter_.error(value.location, "'include' takes a file path, e.g. 'include: wave.yaml'");
      return;
    }
    const LoadedFile& current = *chain_.back()->file;
    const std::string path = resolve_include(current.path, value.scalar);
    for (std::size_t i = 0; i < chain_.size(); ++i) {
      if (chain_[i]->file->path != path) continue;
      std::string cycle;
      for (std::size_t j = i; j < chain_.size(); ++j) cycle += chain_[j]->file->path + " -> ";
      reporter_.error(value.location, "include cycle: " + cycle + path);
      return;
    }
    if (reporter_.include_depth() >= kMaxIncludeDepth) {
      reporter_.error(value.location, "includes nest more than " +
                                          std::to_string(kMaxIncludeDepth) +
                                          " files deep; is there a runaway include chain?");
      return;
    }
    auto loaded = loader_.load(path);
    if (!loaded) {
      reporter_.error(value.location, "cannot include it: " + loaded.error().message);
      return;
    }
    reporter_.push_include(value.location);
    run_file(**loaded, false);
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
  std::map<std::string, std::unique_ptr<FileScope>> scopes_;
  std::vector<FileScope*> chain_;  // files whose steps are running, outermost first
  std::vector<std::optional<int>> pos_;
  std::vector<std::optional<int>> scratch_targets_;  // move_step's, kept to reuse its memory
  std::unique_ptr<Pose> home_;
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
