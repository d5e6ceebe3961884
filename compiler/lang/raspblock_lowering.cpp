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

#include "compiler/lang/positions.hpp"
#include "compiler/lang/raspblock_link.hpp"
#include "compiler/lang/raspblock_settings.hpp"
#include "compiler/lang/scope_chain.hpp"
#include "compiler/lang/step_parts.hpp"
#include "compiler/lang/units.hpp"

namespace seqc::compiler {
namespace {

// The board's positional outputs (docs/protocol/raspblock.md, function 02): the two gimbal
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

std::string grouped(std::uint64_t n) {
  std::string s = std::to_string(n);
  for (int i = static_cast<int>(s.size()) - 3; i > 0; i -= 3)
    s.insert(static_cast<std::size_t>(i), ",");
  return s;
}

using LocationKey = std::tuple<std::uint32_t, std::uint32_t, std::uint32_t>;
LocationKey key_of(const Location& at) { return {at.file, at.line, at.column}; }

class RaspblockLowering {
 public:
  RaspblockLowering(const Robot& robot, FileLoader& loader, Reporter& reporter)
      : robot_(robot), loader_(loader), reporter_(reporter), scopes_({kPan, kTilt}) {}

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
    const YamlNode* map = file_root(f, reporter_);
    if (map == nullptr) return;
    const YamlNode& root = *map;
    reporter_.check_keys(
        root, {"robot", "tempo", "resolution", "poses", "pid", "sequence", "name", "description"},
        "at the top level");
    if (!is_main) {
      check_included_robot(root, robot_.info.profile, reporter_);
      if (const YamlNode* p = root.find("pid")) {
        reporter_.error(p->location,
                        "'pid' belongs in the main file: the settings are sent "
                        "once, before the first step");
      }
    }
    FileScope& scope = scope_for(f);
    if (is_main) {
      end_at_ = root.location;
      if (const YamlNode* p = root.find("pid")) {
        if (auto adjust = parse_pid_section(*p, reporter_)) emit(*adjust, p->location);
      }
    }
    const YamlNode* sequence = find_sequence(root, reporter_);
    if (sequence == nullptr) return;
    if (is_main) end_at_ = sequence->location;
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
      if (ms && *ms == 0) {
        reporter_.error(r->location, "'resolution' must be at least 1ms");
      } else if (ms) {
        scope.resolution_ms = *ms;
      }
    }
    return scope;
  }

  // ---- values --------------------------------------------------------------------------------

  std::vector<std::string> channel_names() const {
    std::vector<std::string> names;
    for (const Channel& c : kChannels) names.emplace_back(c.name);
    return names;
  }

  void parse_poses(const YamlNode& poses, FileScope& scope) {
    compiler::parse_poses(
        poses, scope,
        "'poses' must be a map of pose names to positions, e.g. "
        "'look_left: {pan: 2000, tilt: 1500}'",
        "output: position, e.g. {pan: 2000, tilt: 1500}",
        [this](const YamlNode& map, const std::string& where) {
          std::vector<PositionEntry> entries = parse_targets(map, where);
          for (const PositionEntry& t : entries) {
            if (!t.value.relative) check_limits(t, absolute_units(t), {});
          }
          return entries;
        },
        reporter_);
  }

  std::vector<PositionEntry> parse_targets(const YamlNode& map, const std::string& where) {
    std::vector<PositionEntry> out;
    for (const auto& [key, value] : map.entries) {
      std::optional<std::size_t> channel;
      for (std::size_t i = 0; i < kChannels.size(); ++i) {
        if (kChannels[i].name == key.scalar) channel = i;
      }
      if (!channel) {
        reporter_.unknown(key.location, "output", key.scalar, channel_names(), where);
        continue;
      }
      auto t = parse_position_entry(key, value, *channel, "1500, 90deg, +100", reporter_);
      if (!t) continue;
      out.push_back(std::move(*t));
    }
    return out;
  }

  static double absolute_units(const PositionEntry& t) {
    if (t.home) return kHome;
    return t.value.degrees ? kDegreeZero + t.value.amount * kUnitsPerDegree : t.value.amount;
  }

  bool check_limits(const PositionEntry& t, double units, std::string how,
                    std::optional<Reporter::Note> note = {}) {
    const Channel& c = kChannels[t.output];
    return check_position_limits(t, c.name, c.min, c.max, units, std::move(how), std::move(note),
                                 reporter_);
  }

  std::optional<std::uint32_t> time_ms(const YamlNode& node, std::string_view what) {
    return scopes_.time_ms(node, what, kRaspblockMaxStreamMs,
                           "is longer than a stream may last (24 hours)", reporter_);
  }

  // ---- steps ---------------------------------------------------------------------------------

  void run_steps(const YamlNode& list, std::string_view what) {
    for (const YamlNode& step : step_items(list, what, reporter_)) {
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

  void motion_step(const YamlNode& step, const YamlNode* drive_node, const YamlNode* move_node) {
    std::optional<raspblock::Rocker> drive;
    bool ok = true;
    if (drive_node != nullptr) {
      drive = parse_drive(*drive_node, reporter_);
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
        auto parsed = parse_ease(*ease_node, reporter_);
        ok = ok && parsed.has_value();
        ease = parsed.value_or(Ease::Linear);
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
                            format_ms(static_cast<double>(t) / static_cast<double>(n)) +
                            " are finer than the stream's 1ms clock; use at most " +
                            std::to_string(t) + " steps");
        return;
      }
    } else if (move_node != nullptr) {
      const std::uint32_t res = scopes_.resolution_ms().value_or(kRaspblockDefaultResolutionMs);
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
    std::vector<PositionEntry> inline_entries;
    std::optional<Reporter::Note> note;
    const std::vector<PositionEntry>* entries = scopes_.move_entries(
        target, "output",
        [this](const YamlNode& map, const std::string& where) { return parse_targets(map, where); },
        inline_entries, note, reporter_);
    if (entries == nullptr) return false;
    // An entry parse_targets rejected is already reported; check the others all the same.
    bool ok = !target.is_map() || inline_entries.size() == target.entries.size();
    for (const PositionEntry& e : *entries) {
      double units = 0;
      std::string how;
      if (e.value.relative) {
        const double delta = e.value.degrees ? e.value.amount * kUnitsPerDegree : e.value.amount;
        auto reached = relative_units(e, kChannels[e.output].name, pos_[e.output], delta, how, note,
                                      reporter_);
        if (!reached) {
          ok = false;
          continue;
        }
        units = *reached;
      } else {
        units = absolute_units(e);
      }
      if (out.count(e.output) != 0) {
        reporter_.error(
            e.at, "'" + std::string(kChannels[e.output].name) + "' is given twice in this move");
        ok = false;
        continue;
      }
      if (!check_limits(e, units, how, note)) {
        ok = false;
        continue;
      }
      out[e.output] = static_cast<int>(std::llround(units));
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
    const auto repeat = parse_repeat(step, value, reporter_);
    if (!repeat) return;
    for (long long i = 0; i < repeat->times && !full_; ++i) run_steps(*repeat->body, "'do'");
  }

  void include_step(const YamlNode& value) {
    const LoadedFile* loaded = scopes_.load_include(
        value, "spin.yaml",
        [](const std::string& path, const std::string& reason) {
          return "cannot read included file '" + path + "': " + reason;
        },
        loader_, reporter_);
    if (loaded == nullptr) return;
    reporter_.push_include(value.location);
    run_file(*loaded, false);
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
  ScopeChain scopes_;
  std::array<std::optional<int>, kChannels.size()> pos_;
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
