#include "compiler/lang/raspblock_lowering.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <tuple>

#include "compiler/lang/raspblock_link.hpp"
#include "compiler/lang/units.hpp"

namespace seqc::compiler {
namespace {

// The board's positional outputs (seeds/raspblock-driver-board.md, function 02): the two gimbal
// servos travel together in one packet; servos 1-4 each have their own.
struct Channel {
  std::string_view name;
  int min;
  int max;
  bool gimbal;         // part of the two-servo gimbal packet
  std::uint8_t index;  // gimbal: 0 horizontal, 1 vertical; single: servo number 1-4
};
constexpr std::array<Channel, 6> kChannels = {{
    {"pan", 500, 2500, true, 0},
    {"tilt", 500, 1950, true, 1},
    {"servo1", 500, 2500, false, 1},
    {"servo2", 500, 2500, false, 2},
    {"servo3", 500, 2500, false, 3},
    {"servo4", 500, 2500, false, 4},
}};
constexpr std::size_t kPan = 0;
constexpr std::size_t kTilt = 1;
// Pulse widths in microseconds: 1500 is the neutral position; 0-180 degrees spans 500-2500.
constexpr int kHome = 1500;
constexpr double kDegreeZero = 500.0;
constexpr double kUnitsPerDegree = 2000.0 / 180.0;

struct Axis {
  std::string_view name;
  int limit;
};
// The rocker's ranges: X and Y -25..25 (document); Z -200..200 (protocol-notes.md B reading,
// kept in runtime/protocol/raspblock.cpp).
constexpr std::array<Axis, 3> kAxes = {{{"x", 25}, {"y", 25}, {"z", 200}}};

constexpr std::array<std::string_view, 8> kGainNames = {"speed_kp",    "speed_ki",    "position_kp",
                                                        "position_ki", "position_kd", "yaw_kp",
                                                        "yaw_ki",      "yaw_kd"};

enum class Ease { Linear, In, Out, InOut };

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

std::string grouped(std::uint64_t n) {
  std::string s = std::to_string(n);
  for (int i = static_cast<int>(s.size()) - 3; i > 0; i -= 3)
    s.insert(static_cast<std::size_t>(i), ",");
  return s;
}

std::string ms_text(double ms) {
  if (ms == std::floor(ms)) return std::to_string(static_cast<long long>(ms)) + "ms";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1fms", ms);
  return buf;
}

using LocationKey = std::tuple<std::uint32_t, std::uint32_t, std::uint32_t>;
LocationKey key_of(const Location& at) { return {at.file, at.line, at.column}; }

struct Target {
  std::size_t channel = 0;
  std::string written;
  bool home = false;
  PositionValue value;
  Location at;
};

struct Pose {
  std::vector<Target> entries;
  Location at;
};

struct FileScope {
  const LoadedFile* file = nullptr;
  std::map<std::string, Pose, std::less<>> poses;
  std::optional<double> tempo;
  std::optional<std::uint32_t> resolution_ms;
};

class RaspblockLowering {
 public:
  RaspblockLowering(const Robot& robot, FileLoader& loader, Reporter& reporter)
      : robot_(robot), loader_(loader), reporter_(reporter) {}

  RaspblockProgram run(const LoadedFile& main) {
    if (main.root && main.root->is_map()) {
      if (const YamlNode* r = main.root->find("robot"); r != nullptr && r->is_map()) {
        for (std::string_view fixed : {"servos", "mirror"}) {
          if (const YamlNode* n = r->find(fixed)) {
            reporter_.error(n->location,
                            "the raspblock's outputs are fixed (pan, tilt, "
                            "servo1-servo4); remove '" +
                                std::string(fixed) + "'");
          }
        }
      }
    }
    run_file(main, true);
    if (!full_) {
      // Safety: whatever the steps did, the stream ends with every speed at zero.
      emit(raspblock::Rocker{0, 0, 0}, end_at_);
    }
    check_capacity();
    RaspblockProgram program;
    program.packets = std::move(packets_);
    program.duration_ms = static_cast<std::uint32_t>(std::min(now_ms_, kRaspblockMaxStreamMs));
    return program;
  }

 private:
  // ---- files ---------------------------------------------------------------------------------

  void run_file(const LoadedFile& f, bool is_main) {
    if (!f.root) return;
    const YamlNode& root = *f.root;
    if (!root.is_map()) {
      reporter_.error(root.location,
                      "a choreography file must be a map with 'robot' and 'sequence' keys");
      return;
    }
    reporter_.check_keys(
        root, {"robot", "tempo", "resolution", "poses", "pid", "sequence", "name", "description"},
        "at the top level");
    if (!is_main) {
      if (const YamlNode* r = root.find("robot")) {
        auto name = included_robot_name(*r, reporter_);
        if (name && *name != robot_.info.profile) {
          reporter_.error(r->location, "this file is for robot '" + *name +
                                           "' but is included by a file for '" +
                                           robot_.info.profile + "'");
        }
      }
      if (const YamlNode* p = root.find("pid")) {
        reporter_.error(p->location,
                        "'pid' belongs in the main file: the settings are sent "
                        "once, before the first step");
      }
    }
    FileScope& scope = scope_for(f);
    if (is_main) {
      end_at_ = root.location;
      if (const YamlNode* p = root.find("pid")) pid_section(*p);
    }
    const YamlNode* sequence = root.find("sequence");
    if (sequence == nullptr) {
      reporter_.error(root.location, "missing 'sequence': the list of steps to perform");
      return;
    }
    if (is_main) end_at_ = sequence->location;
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
      if (ms && *ms == 0) {
        reporter_.error(r->location, "'resolution' must be at least 1ms");
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

  // ---- pid -----------------------------------------------------------------------------------

  void pid_section(const YamlNode& pid) {
    if (!pid.is_map()) {
      reporter_.error(pid.location,
                      "'pid' must be a map: mode (speed or position) and the "
                      "gains speed_kp ... yaw_kd, each 0-255");
      return;
    }
    reporter_.check_keys(pid,
                         {"mode", "speed_kp", "speed_ki", "position_kp", "position_ki",
                          "position_kd", "yaw_kp", "yaw_ki", "yaw_kd"},
                         "in 'pid'");
    raspblock::PidAdjust p;
    bool ok = true;
    std::string missing;
    if (const YamlNode* m = pid.find("mode")) {
      if (m->is_scalar() && m->scalar == "speed") {
        p.mode = raspblock::PidMode::Speed;
      } else if (m->is_scalar() && m->scalar == "position") {
        p.mode = raspblock::PidMode::Position;
      } else {
        reporter_.unknown(m->location, "pid mode", m->is_scalar() ? m->scalar : "",
                          {"speed", "position"});
        ok = false;
      }
    } else {
      missing = "mode";
    }
    std::uint8_t* gains[] = {&p.speed_kp,    &p.speed_ki, &p.position_kp, &p.position_ki,
                             &p.position_kd, &p.yaw_kp,   &p.yaw_ki,      &p.yaw_kd};
    for (std::size_t i = 0; i < kGainNames.size(); ++i) {
      const YamlNode* g = pid.find(kGainNames[i]);
      if (g == nullptr) {
        missing += std::string(missing.empty() ? "" : ", ") + std::string(kGainNames[i]);
        continue;
      }
      auto v = parse_integer(*g, 0, 255, "'" + std::string(kGainNames[i]) + "'", reporter_);
      if (v) {
        *gains[i] = static_cast<std::uint8_t>(*v);
      } else {
        ok = false;
      }
    }
    if (!missing.empty()) {
      reporter_.error(pid.location,
                      "'pid' sets every value at once, so it needs all of mode, "
                      "speed_kp, speed_ki, position_kp, position_ki, "
                      "position_kd, yaw_kp, yaw_ki, yaw_kd; missing: " +
                          missing);
      return;
    }
    if (ok) emit(p, pid.location);
  }

  // ---- values --------------------------------------------------------------------------------

  std::vector<std::string> channel_names() const {
    std::vector<std::string> names;
    for (const Channel& c : kChannels) names.emplace_back(c.name);
    return names;
  }

  void parse_poses(const YamlNode& poses, FileScope& scope) {
    if (poses.kind == YamlNode::Kind::Null) return;
    if (!poses.is_map()) {
      reporter_.error(poses.location,
                      "'poses' must be a map of pose names to positions, e.g. "
                      "'look_left: {pan: 2000, tilt: 1500}'");
      return;
    }
    for (const auto& [key, value] : poses.entries) {
      Pose pose;
      pose.at = key.location;
      if (!value.is_map()) {
        reporter_.error(value.location, "pose '" + key.scalar +
                                            "' must be a map of output: position, e.g. "
                                            "{pan: 2000, tilt: 1500}");
      } else {
        pose.entries = parse_targets(value, "in pose '" + key.scalar + "'");
        for (const Target& t : pose.entries) {
          if (!t.value.relative) check_limits(t, absolute_units(t), {});
        }
      }
      scope.poses.emplace(key.scalar, std::move(pose));
    }
  }

  std::vector<Target> parse_targets(const YamlNode& map, const std::string& where) {
    std::vector<Target> out;
    for (const auto& [key, value] : map.entries) {
      std::optional<std::size_t> channel;
      for (std::size_t i = 0; i < kChannels.size(); ++i) {
        if (kChannels[i].name == key.scalar) channel = i;
      }
      if (!channel) {
        reporter_.unknown(key.location, "output", key.scalar, channel_names(), where);
        continue;
      }
      Target t;
      t.channel = *channel;
      t.at = value.location;
      if (!value.is_scalar()) {
        reporter_.error(value.location, "the position of '" + key.scalar +
                                            "' must be a value such as 1500, 90deg, +100 or "
                                            "home");
        continue;
      }
      t.written = value.scalar;
      if (value.scalar == "home") {
        t.home = true;
      } else if (auto p = parse_position(value.scalar); !p) {
        reporter_.error(value.location, p.error().message);
        continue;
      } else {
        t.value = *p;
      }
      out.push_back(std::move(t));
    }
    return out;
  }

  static double absolute_units(const Target& t) {
    if (t.home) return kHome;
    return t.value.degrees ? kDegreeZero + t.value.amount * kUnitsPerDegree : t.value.amount;
  }

  bool check_limits(const Target& t, double units, std::string how,
                    std::optional<Reporter::Note> note = {}) {
    const Channel& c = kChannels[t.channel];
    const long long p = std::llround(units);
    if (p >= c.min && p <= c.max) return true;
    if (how.empty() && t.value.degrees) how = t.written;
    std::string message = "'" + std::string(c.name) + "' would move to " + std::to_string(p);
    if (!how.empty()) message += " (" + how + ")";
    message += p > c.max ? ", above its max " + std::to_string(c.max)
                         : ", below its min " + std::to_string(c.min);
    reporter_.error(t.at, std::move(message), std::move(note));
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
    if (ms > static_cast<double>(kRaspblockMaxStreamMs)) {
      reporter_.error(node.location,
                      "'" + node.scalar + "' is longer than a stream may last (24 hours)");
      return std::nullopt;
    }
    return static_cast<std::uint32_t>(std::llround(ms));
  }

  // A whole number within [-limit, limit], written with an optional sign.
  std::optional<int> parse_signed(const YamlNode& node, int limit, const std::string& what) {
    const std::string range = std::to_string(-limit) + " to " + std::to_string(limit);
    if (!node.is_scalar()) {
      reporter_.error(node.location, what + " must be a whole number " + range);
      return std::nullopt;
    }
    std::string_view s = node.scalar;
    int sign = 1;
    if (!s.empty() && (s[0] == '-' || s[0] == '+')) {
      sign = s[0] == '-' ? -1 : 1;
      s.remove_prefix(1);
    }
    long long v = 0;
    bool ok = !s.empty() && s.size() <= 9;
    for (char c : s) {
      ok = ok && c >= '0' && c <= '9';
      if (ok) v = v * 10 + (c - '0');
    }
    if (!ok) {
      reporter_.error(node.location,
                      "'" + node.scalar + "' is not a whole number; " + what + " is " + range);
      return std::nullopt;
    }
    v *= sign;
    if (v < -limit || v > limit) {
      reporter_.error(node.location, what + " must be " + range + ", not " + node.scalar);
      return std::nullopt;
    }
    return static_cast<int>(v);
  }

  // ---- steps ---------------------------------------------------------------------------------

  void run_steps(const YamlNode& list, std::string_view what) {
    if (list.kind == YamlNode::Kind::Null) return;
    if (!list.is_sequence()) {
      reporter_.error(list.location, std::string(what) +
                                         " must be a list of steps (each line "
                                         "starting with '- '), not " +
                                         std::string(kind_name(list)));
      return;
    }
    for (const YamlNode& step : list.items) {
      if (full_) return;
      run_step(step);
    }
  }

  void run_step(const YamlNode& step) {
    static constexpr std::string_view kAlone[] = {"wait", "repeat", "include"};
    if (!step.is_map()) {
      reporter_.error(step.location,
                      "a step must be a map such as 'drive: {x: 10}' or 'wait: 1s', not " +
                          std::string(kind_name(step)));
      return;
    }
    const YamlNode* alone = nullptr;
    const YamlNode* other = nullptr;
    for (const auto& [key, value] : step.entries) {
      bool is_alone = false;
      for (std::string_view v : kAlone) is_alone = is_alone || key.scalar == v;
      const bool is_motion = key.scalar == "drive" || key.scalar == "move";
      if (is_alone && alone == nullptr) {
        alone = &key;
      } else if (is_alone || is_motion) {
        other = other == nullptr ? &key : other;
      }
    }
    if (alone != nullptr && other != nullptr) {
      const YamlNode& later = other->location.line > alone->location.line ||
                                      (other->location.line == alone->location.line &&
                                       other->location.column > alone->location.column)
                                  ? *other
                                  : *alone;
      const YamlNode& earlier = &later == other ? *alone : *other;
      reporter_.error(later.location, "a step does one thing: '" + later.scalar +
                                          "' cannot be combined with '" + earlier.scalar +
                                          "'; make it a separate step");
      return;
    }
    if (alone == nullptr) {
      const YamlNode* drive = step.find("drive");
      const YamlNode* move = step.find("move");
      if (drive == nullptr && move == nullptr) {
        if (reporter_.check_keys(
                step, {"drive", "move", "wait", "repeat", "include", "time", "ease", "steps", "do"},
                "in a step")) {
          reporter_.error(step.location,
                          "a step needs one of: drive, move, wait, repeat, "
                          "include");
        }
        return;
      }
      if (reporter_.check_keys(step, {"drive", "move", "time", "ease", "steps"},
                               drive != nullptr && move != nullptr
                                   ? "in a drive-and-move step"
                                   : (drive ? "in a drive step" : "in a move step"))) {
        motion_step(step, drive, move);
      }
      return;
    }
    const std::string& verb = alone->scalar;
    const YamlNode& value = *step.find(verb);
    if (verb == "wait") {
      if (reporter_.check_keys(step, {"wait"}, "in a wait step")) wait_step(step, value);
    } else if (verb == "repeat") {
      if (reporter_.check_keys(step, {"repeat", "do"}, "in a repeat step")) {
        repeat_step(step, value);
      }
    } else if (reporter_.check_keys(step, {"include"}, "in an include step")) {
      include_step(value);
    }
  }

  const Pose* find_pose(const YamlNode& name) {
    for (auto it = chain_.rbegin(); it != chain_.rend(); ++it) {
      auto p = (*it)->poses.find(name.scalar);
      if (p != (*it)->poses.end()) return &p->second;
    }
    if (name.scalar == "home") {
      if (!home_) {
        home_ = std::make_unique<Pose>();
        for (std::size_t c : {kPan, kTilt}) {
          Target t;
          t.channel = c;
          t.home = true;
          t.written = "home";
          home_->entries.push_back(t);
        }
      }
      return home_.get();
    }
    std::vector<std::string> names{"home"};
    for (const FileScope* s : chain_) {
      for (const auto& [n, pose] : s->poses) names.push_back(n);
    }
    reporter_.unknown(name.location, "pose", name.scalar, names);
    return nullptr;
  }

  std::optional<raspblock::Rocker> parse_drive(const YamlNode& drive) {
    if (!drive.is_map()) {
      reporter_.error(drive.location,
                      "'drive' takes a map of speeds, e.g. {x: 10, y: 0, z: 0} "
                      "(x, y -25 to 25; z -200 to 200)");
      return std::nullopt;
    }
    reporter_.check_keys(drive, {"x", "y", "z"}, "in 'drive'");
    int values[3] = {0, 0, 0};
    bool ok = true;
    for (std::size_t i = 0; i < kAxes.size(); ++i) {
      if (const YamlNode* n = drive.find(kAxes[i].name)) {
        auto v = parse_signed(*n, kAxes[i].limit, "'" + std::string(kAxes[i].name) + "'");
        if (v) {
          values[i] = *v;
        } else {
          ok = false;
        }
      }
    }
    if (!ok) return std::nullopt;
    return raspblock::Rocker{values[0], values[1], values[2]};
  }

  void motion_step(const YamlNode& step, const YamlNode* drive_node, const YamlNode* move_node) {
    std::optional<raspblock::Rocker> drive;
    bool ok = true;
    if (drive_node != nullptr) {
      drive = parse_drive(*drive_node);
      ok = drive.has_value();
    }

    const YamlNode* ease_node = step.find("ease");
    const YamlNode* steps_node = step.find("steps");
    if (move_node == nullptr) {
      for (const YamlNode* n : {ease_node, steps_node}) {
        if (n == nullptr) continue;
        for (const auto& [key, value] : step.entries) {
          if (&value != n) continue;
          reporter_.error(key.location, "'" + key.scalar +
                                            "' shapes a gimbal or servo move; this step only "
                                            "drives (speeds change at once)");
        }
        ok = false;
      }
    }

    std::map<std::size_t, int> targets;
    Ease ease = Ease::Linear;
    std::optional<long long> steps;
    if (move_node != nullptr) {
      ok = resolve_move(*move_node, targets) && ok;
      if (ease_node != nullptr) {
        static const std::map<std::string, Ease, std::less<>> kEases = {
            {"linear", Ease::Linear},     {"in", Ease::In},      {"out", Ease::Out},
            {"in-out", Ease::InOut},      {"ease-in", Ease::In}, {"ease-out", Ease::Out},
            {"ease-in-out", Ease::InOut},
        };
        auto it = ease_node->is_scalar() ? kEases.find(ease_node->scalar) : kEases.end();
        if (it == kEases.end()) {
          reporter_.unknown(ease_node->location, "easing",
                            ease_node->is_scalar() ? ease_node->scalar : "",
                            {"linear", "in", "out", "in-out"});
          ok = false;
        } else {
          ease = it->second;
        }
      }
      if (steps_node != nullptr) {
        steps = parse_integer(*steps_node, 1, 100000, "'steps'", reporter_);
        ok = ok && steps.has_value();
      }
    }
    // The time after the targets, so mistakes come out in the order they are written.
    const YamlNode* time_node = step.find("time");
    std::optional<std::uint32_t> total;
    if (time_node == nullptr) {
      reporter_.error(step.location, std::string("this ") + (move_node ? "move" : "drive") +
                                         " needs a 'time', e.g. 'time: 500ms'");
    } else {
      total = time_ms(*time_node, "'time'");
      if (total && *total == 0) {
        reporter_.error(time_node->location, "'time' must be at least 1ms");
        total.reset();
      }
    }
    if (!ok || !total) return;

    const std::uint32_t t = total.value_or(0);
    std::uint64_t n = 1;
    if (steps) {
      n = static_cast<std::uint64_t>(*steps);
      if (n > t) {
        reporter_.error(steps_node->location,
                        std::to_string(n) + " steps of " +
                            ms_text(static_cast<double>(t) / static_cast<double>(n)) +
                            " are finer than the stream's 1ms clock; use at most " +
                            std::to_string(t) + " steps");
        return;
      }
    } else if (move_node != nullptr) {
      std::uint32_t res = kRaspblockDefaultResolutionMs;
      for (auto it = chain_.rbegin(); it != chain_.rend(); ++it) {
        if ((*it)->resolution_ms) {
          res = *(*it)->resolution_ms;
          break;
        }
      }
      n = std::max<std::uint64_t>(1, (t + res / 2) / res);
    }

    begin_step(drive.has_value());
    const std::uint64_t start = now_ms_;
    if (drive) {
      emit(*drive, step.location);
      stop_due_ = true;
    }
    if (move_node != nullptr) interpolate(step.location, start, t, n, ease, targets);
    advance(t, step.location);
  }

  // Resolves a move's targets into device units; false after reporting a mistake.
  bool resolve_move(const YamlNode& target, std::map<std::size_t, int>& out) {
    std::vector<Target> inline_entries;
    const std::vector<Target>* entries = nullptr;
    std::optional<Reporter::Note> note;
    if (target.is_scalar()) {
      const Pose* pose = find_pose(target);
      if (pose == nullptr) return false;
      entries = &pose->entries;
      if (pose != home_.get()) {
        note = Reporter::Note{target.location, "in this move to pose '" + target.scalar + "'"};
      }
    } else if (target.is_map()) {
      inline_entries = parse_targets(target, "in this move");
      entries = &inline_entries;
    } else {
      reporter_.error(target.location,
                      "'move' takes a pose name or a map of output: position, "
                      "not " +
                          std::string(kind_name(target)));
      return false;
    }
    // An entry parse_targets rejected is already reported; check the others all the same.
    bool ok = !target.is_map() || inline_entries.size() == target.entries.size();
    for (const Target& e : *entries) {
      double units = 0;
      std::string how;
      if (e.value.relative) {
        const double delta = e.value.degrees ? e.value.amount * kUnitsPerDegree : e.value.amount;
        const std::optional<int>& base = pos_[e.channel];
        if (!base) {
          reporter_.error(e.at,
                          "'" + std::string(kChannels[e.channel].name) +
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
        units = absolute_units(e);
      }
      if (out.count(e.channel) != 0) {
        reporter_.error(
            e.at, "'" + std::string(kChannels[e.channel].name) + "' is given twice in this move");
        ok = false;
        continue;
      }
      if (!check_limits(e, units, how, note)) {
        ok = false;
        continue;
      }
      out[e.channel] = static_cast<int>(std::llround(units));
    }
    // One packet sets both gimbal servos, so the one not moving must have a known position.
    const bool pan = out.count(kPan) != 0;
    const bool tilt = out.count(kTilt) != 0;
    if (ok && pan != tilt) {
      const std::size_t other = pan ? kTilt : kPan;
      if (!pos_[other]) {
        reporter_.error(target.location,
                        "the gimbal command sets pan and tilt together and '" +
                            std::string(kChannels[other].name) +
                            "' has no position yet; give both in the first gimbal move, e.g. "
                            "{pan: 1800, tilt: home}",
                        note);
        ok = false;
      }
    }
    return ok;
  }

  // Splits a move into n packets per output: the k-th (1..n) carries the position at k/n of
  // the way and is sent at (k-1)/n of the time, so the servo reaches the target as the step
  // ends. An output without a known start goes straight to its target in the first packet.
  // A packet that would repeat the previous value of its output is left out.
  void interpolate(Location at, std::uint64_t start, std::uint32_t t, std::uint64_t n, Ease ease,
                   const std::map<std::size_t, int>& targets) {
    std::map<std::size_t, std::optional<int>> from;
    for (const auto& [c, end] : targets) from[c] = pos_[c];
    for (std::uint64_t k = 1; k <= n && !full_; ++k) {
      const std::uint64_t send = start + (std::uint64_t{t} * (k - 1) + n / 2) / n;
      const double f = ease_at(ease, static_cast<double>(k) / static_cast<double>(n));
      std::array<std::optional<int>, kChannels.size()> next;
      for (const auto& [c, end] : targets) {
        next[c] = from[c] && k < n ? static_cast<int>(std::llround(*from[c] + (end - *from[c]) * f))
                                   : end;
      }
      if (next[kPan] || next[kTilt]) {
        const int h = next[kPan].value_or(pos_[kPan].value_or(kHome));
        const int v = next[kTilt].value_or(pos_[kTilt].value_or(kHome));
        if (pos_[kPan] != h || pos_[kTilt] != v) {
          emit_at(
              send,
              raspblock::GimbalServos{static_cast<std::uint16_t>(h), static_cast<std::uint16_t>(v)},
              at);
          pos_[kPan] = h;
          pos_[kTilt] = v;
        }
      }
      for (std::size_t c = kTilt + 1; c < kChannels.size(); ++c) {
        if (!next[c] || pos_[c] == next[c]) continue;
        emit_at(send,
                raspblock::SingleServo{kChannels[c].index, static_cast<std::uint16_t>(*next[c])},
                at);
        pos_[c] = next[c];
      }
    }
  }

  void wait_step(const YamlNode& step, const YamlNode& value) {
    auto total = time_ms(value, "'wait'");
    if (!total) return;
    begin_step(false);
    advance(*total, step.location);
  }

  void repeat_step(const YamlNode& step, const YamlNode& value) {
    auto times = parse_integer(value, 1, 65535, "the repeat count", reporter_);
    const YamlNode* body = step.find("do");
    if (body == nullptr) {
      reporter_.error(step.location, "'repeat' needs a 'do' list of the steps to repeat");
      return;
    }
    if (!times) return;
    for (long long i = 0; i < *times && !full_; ++i) run_steps(*body, "'do'");
  }

  void include_step(const YamlNode& value) {
    if (!value.is_scalar() || value.scalar.empty()) {
      reporter_.error(value.location, "'include' takes a file path, e.g. 'include: spin.yaml'");
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
    if (reporter_.include_depth() >= 16) {
      reporter_.error(value.location,
                      "includes nest more than 16 files deep; is there a "
                      "runaway include chain?");
      return;
    }
    auto loaded = loader_.load(path);
    if (!loaded) {
      reporter_.error(value.location,
                      "cannot read included file '" + path + "': " + loaded.error().message);
      return;
    }
    reporter_.push_include(value.location);
    run_file(**loaded, false);
    reporter_.pop_include();
  }

  // ---- the stream ----------------------------------------------------------------------------

  // A drive lasts for its step: unless this step drives too (its speeds replace the old ones
  // at the same instant), the car is stopped before the step starts.
  void begin_step(bool drives) {
    if (stop_due_ && !drives) emit(raspblock::Rocker{0, 0, 0}, last_drive_at_);
    stop_due_ = false;
  }

  void advance(std::uint32_t t, Location at) {
    now_ms_ += t;
    if (now_ms_ > kRaspblockMaxStreamMs && !full_) {
      reporter_.error(at, "the stream would last longer than 24 hours after this step");
      full_ = true;
    }
  }

  void emit(raspblock::Packet packet, Location at) { emit_at(now_ms_, std::move(packet), at); }

  void emit_at(std::uint64_t at_ms, raspblock::Packet packet, Location at) {
    if (full_) return;
    if (packets_.size() >= kRaspblockMaxPackets) {
      reporter_.error(at, "the stream would need more than " + grouped(kRaspblockMaxPackets) +
                              " packets by this step; use a coarser 'resolution' or fewer "
                              "repeats");
      full_ = true;
      return;
    }
    if (std::holds_alternative<raspblock::Rocker>(packet)) last_drive_at_ = at;
    include_sites_.try_emplace(key_of(at), reporter_.include_sites());
    packets_.push_back(TimedPacket{static_cast<std::uint32_t>(at_ms), std::move(packet), at});
  }

  void check_capacity() {
    for (const Overload& o : find_overloads(packets_)) {
      const Location& at = packets_[o.first].source;
      const std::vector<Location> sites = reporter_.include_sites();
      reporter_.set_include_sites(include_sites_[key_of(at)]);
      reporter_.error(at, "the stream needs " + grouped(o.bytes) + " bytes in the " +
                              std::to_string(kCapacityWindowMs) + "ms from " +
                              format_seconds(o.from_ms) + " (" + grouped(o.bytes_per_second()) +
                              " B/s), more than the 115200-baud link carries (" +
                              grouped(kRaspblockBytesPerSecond) +
                              " B/s); use a coarser 'resolution' or fewer 'steps'");
      reporter_.set_include_sites(sites);
    }
  }

  const Robot& robot_;
  FileLoader& loader_;
  Reporter& reporter_;
  std::map<std::string, std::unique_ptr<FileScope>> scopes_;
  std::vector<FileScope*> chain_;
  std::array<std::optional<int>, kChannels.size()> pos_;
  std::unique_ptr<Pose> home_;
  std::uint64_t now_ms_ = 0;
  bool stop_due_ = false;
  bool full_ = false;
  Location last_drive_at_;
  Location end_at_;
  std::vector<TimedPacket> packets_;
  std::map<LocationKey, std::vector<Location>> include_sites_;
};

}  // namespace

RaspblockProgram lower_raspblock_program(const Robot& robot, const LoadedFile& main,
                                         FileLoader& loader, Reporter& reporter) {
  return RaspblockLowering(robot, loader, reporter).run(main);
}

}  // namespace seqc::compiler
