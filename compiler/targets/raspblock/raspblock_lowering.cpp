// The Raspblock front end: files, values and the packet stream it builds; the steps are
// lowered in raspblock_steps.cpp.
#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "compiler/targets/raspblock/raspblock_lowering_state.hpp"

namespace seqc::compiler {

RaspblockProgram RaspblockLowering::run(const LoadedFile& main) {
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
  merge_gimbal_packets();
  // Tracks of a `together` each run from the block's start: the stream goes out in time order
  // (packets at one instant keep the order the steps wrote them in).
  std::stable_sort(packets_.begin(), packets_.end(),
                   [](const TimedPacket& a, const TimedPacket& b) { return a.at_ms < b.at_ms; });
  drop_superseded_speeds();
  check_capacity();
  RaspblockProgram program;
  program.packets = std::move(packets_);
  program.duration_ms = static_cast<std::uint32_t>(std::min<std::uint64_t>(
      static_cast<std::uint64_t>(std::max<std::int64_t>(now_.round(), 0)), kRaspblockMaxStreamMs));
  timeline_.end = ExactMs(static_cast<std::int64_t>(program.duration_ms));
  program.timeline = std::move(timeline_);
  return program;
}

void RaspblockLowering::run_file(const LoadedFile& f, bool is_main) {
  const YamlNode* map = file_root(f, reporter_);
  if (map == nullptr) return;
  const YamlNode& root = *map;
  if (!is_main && !is_choreography(f)) {
    // An include with no 'sequence' may be any file: its one error names none of its keys.
    find_sequence(root, reporter_);
    return;
  }
  reporter_.check_keys(root,
                       {"robot", "music", "tempo", "meter", "resolution", "poses", "sections",
                        "pid", "sequence", "name", "description"},
                       "at the top level");
  reporter_.check_free_text(root);
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
  run_sequence(root, scope, *sequence, is_main);
}

FileScope& RaspblockLowering::scope_for(const LoadedFile& f) {
  auto [scope, fresh] = scopes_.open(f, reporter_);
  if (!fresh) return scope;
  const YamlNode& root = *f.root;
  if (const YamlNode* p = root.find("poses")) parse_poses(*p, scope);
  if (const YamlNode* r = root.find("resolution")) {
    scopes_.push(scope);  // so beats use this file's tempo
    auto ms = scopes_.time_ms(*r, "'resolution'", kRaspblockMaxStreamMs,
                              "is longer than a stream may last (24 hours)", reporter_);
    scopes_.pop();
    if (ms && *ms == 0) {
      reporter_.error(r->location, "'resolution' must be at least 1ms");
    } else if (ms) {
      scope.resolution_ms = *ms;
    }
  }
  if (const YamlNode* s = root.find("sections")) read_sections(*s, scope, reporter_);
  return scope;
}

std::vector<std::string> RaspblockLowering::channel_names() const {
  std::vector<std::string> names;
  for (const Channel& c : kChannels) names.emplace_back(c.name);
  return names;
}

void RaspblockLowering::parse_poses(const YamlNode& poses, FileScope& scope) {
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

std::vector<PositionEntry> RaspblockLowering::parse_targets(const YamlNode& map,
                                                            const std::string& where) {
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

double RaspblockLowering::absolute_units(const PositionEntry& t) {
  if (t.home) return kHome;
  return t.value.degrees ? kDegreeZero + t.value.amount * kUnitsPerDegree : t.value.amount;
}

bool RaspblockLowering::check_limits(const PositionEntry& t, double units, std::string how,
                                     std::optional<Reporter::Note> note) {
  const Channel& c = kChannels[t.output];
  return check_position_limits(t, c.name, c.min, c.max, units, std::move(how), std::move(note),
                               reporter_);
}

std::optional<ExactMs> RaspblockLowering::exact_time(const YamlNode& node, std::string_view what) {
  const std::optional<ExactMs> end = musical_time(node, what, now_);
  if (!end) return std::nullopt;
  const std::optional<ExactMs> exact = *end - now_;
  if (exact->value() > static_cast<double>(kRaspblockMaxStreamMs)) {
    reporter_.error(node.location,
                    "'" + node.scalar + "' is longer than a stream may last (24 hours)");
    return std::nullopt;
  }
  return exact;
}

// A drive lasts for its step: unless this step drives too (its speeds replace the old ones
// at the same instant), the car is stopped before the step starts.
void RaspblockLowering::begin_step(bool drives) {
  if (stop_due_ && !drives) emit(raspblock::Rocker{0, 0, 0}, last_drive_at_);
  stop_due_ = false;
}

void RaspblockLowering::advance(ExactMs t, Location at) {
  now_ += t;
  if (now_.value() > static_cast<double>(kRaspblockMaxStreamMs) && !full_) {
    reporter_.error(at, "the stream would last longer than 24 hours after this step");
    full_ = true;
  }
}

void RaspblockLowering::emit_at(ExactMs at_time, raspblock::Packet packet, Location at) {
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
  const std::int64_t at_ms = std::clamp<std::int64_t>(
      at_time.round(), 0, static_cast<std::int64_t>(kRaspblockMaxStreamMs));
  packets_.push_back(TimedPacket{static_cast<std::uint32_t>(at_ms), std::move(packet), at});
}

void RaspblockLowering::merge_gimbal_packets() {
  std::vector<std::size_t> order;
  for (const auto& [index, set] : gimbal_sets_) order.push_back(index);
  // The order of the stream's own sort: by time, then as written.
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return packets_[a].at_ms < packets_[b].at_ms;
  });
  std::optional<int> pan, tilt;
  std::vector<bool> dropped(packets_.size(), false);
  for (std::size_t first = 0; first < order.size();) {
    // The gimbal packets of one millisecond: what each sets, then one packet at the first's place.
    std::size_t end = first;
    while (end < order.size() && packets_[order[end]].at_ms == packets_[order[first]].at_ms) {
      const GimbalSet& set = gimbal_sets_[order[end]];
      if (set.pan) pan = set.pan;
      if (set.tilt) tilt = set.tilt;
      if (end > first) dropped[order[end]] = true;
      ++end;
    }
    TimedPacket& p = packets_[order[first]];
    if (!pan || !tilt) {
      reporter_.error(p.source,
                      fmt::format("the gimbal command sets pan and tilt together and '{}' has no "
                                  "position yet at {}; give it one before this, or move it at "
                                  "the same instant",
                                  pan ? "tilt" : "pan", format_seconds(p.at_ms)));
    } else {
      p.packet = raspblock::GimbalServos{static_cast<std::uint16_t>(*pan),
                                         static_cast<std::uint16_t>(*tilt)};
    }
    first = end;
  }
  if (std::find(dropped.begin(), dropped.end(), true) == dropped.end()) return;
  std::vector<TimedPacket> kept;
  kept.reserve(packets_.size());
  for (std::size_t i = 0; i < packets_.size(); ++i) {
    if (!dropped[i]) kept.push_back(std::move(packets_[i]));
  }
  packets_ = std::move(kept);
}

// The car follows the last speeds it was sent: of several Rocker packets in one millisecond
// (a drive's stop where the next step's drive starts, at a section or block join), only the
// last does anything, so the others are left out rather than sent a byte-time apart.
void RaspblockLowering::drop_superseded_speeds() {
  std::vector<TimedPacket> kept;
  kept.reserve(packets_.size());
  for (std::size_t i = 0; i < packets_.size(); ++i) {
    const bool speeds = std::holds_alternative<raspblock::Rocker>(packets_[i].packet);
    bool superseded = false;
    for (std::size_t j = i + 1; speeds && j < packets_.size(); ++j) {
      if (packets_[j].at_ms != packets_[i].at_ms) break;
      if (std::holds_alternative<raspblock::Rocker>(packets_[j].packet)) superseded = true;
    }
    if (!superseded) kept.push_back(std::move(packets_[i]));
  }
  packets_ = std::move(kept);
}

void RaspblockLowering::check_capacity() {
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

RaspblockProgram lower_raspblock_program(const Robot& robot, const LoadedFile& main,
                                         FileLoader& loader, Reporter& reporter, StepTimes* times) {
  RaspblockLowering lowering(robot, loader, reporter);
  lowering.record_times(times);
  return lowering.run(main);
}

}  // namespace seqc::compiler
