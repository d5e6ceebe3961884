// The Raspblock front end's steps: drive, move (gimbal and servos, eased), wait, repeat and
// include, each into packets on the stream.
#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "compiler/lang/raspblock_lowering_state.hpp"

namespace seqc::compiler {

void RaspblockLowering::run_steps(const YamlNode& list, std::string_view what) {
  for (const YamlNode& step : step_items(list, what, reporter_)) {
    if (full_) return;
    run_step(step);
  }
}

void RaspblockLowering::run_step(const YamlNode& step) {
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

void RaspblockLowering::motion_step(const YamlNode& step, const YamlNode* drive_node,
                                    const YamlNode* move_node) {
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
  Easing ease;
  std::optional<long long> steps;
  if (move_node != nullptr) {
    ok = resolve_move(*move_node, targets) && ok;
    if (ease_node != nullptr) {
      auto parsed = parse_ease(*ease_node, reporter_);
      ok = ok && parsed.has_value();
      ease = parsed.value_or(Easing{});
    }
    if (steps_node != nullptr) {
      steps = parse_integer(*steps_node, 1, 100000, "'steps'", reporter_);
      ok = ok && steps.has_value();
    }
  }
  // The time after the targets, so mistakes come out in the order they are written.
  const YamlNode* time_node = step.find("time");
  std::optional<ExactMs> total;
  if (time_node == nullptr) {
    reporter_.error(step.location, std::string("this ") + (move_node ? "move" : "drive") +
                                       " needs a 'time', e.g. 'time: 500ms'");
  } else {
    total = exact_time(*time_node, "'time'");
    // Under half a millisecond the stream's clock cannot tell the step from nothing.
    if (total && total->round() <= 0) {
      reporter_.error(time_node->location, "'time' must be at least 1ms");
      total.reset();
    }
  }
  if (!ok || !total) return;

  const ExactMs exact_t = *total;
  // Packet counts come from the step's length on the stream's 1 ms clock.
  const auto t = static_cast<std::uint32_t>(exact_t.round());
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
  const ExactMs start = now_;
  if (drive) {
    emit(*drive, step.location);
    stop_due_ = true;
  }
  if (move_node != nullptr) interpolate(step.location, start, exact_t, n, ease, targets);
  advance(exact_t, step.location);
}

// Resolves a move's targets into device units; false after reporting a mistake.
bool RaspblockLowering::resolve_move(const YamlNode& target, std::map<std::size_t, int>& out) {
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
      auto reached =
          relative_units(e, kChannels[e.output].name, pos_[e.output], delta, how, note, reporter_);
      if (!reached) {
        ok = false;
        continue;
      }
      units = *reached;
    } else {
      units = absolute_units(e);
    }
    if (out.count(e.output) != 0) {
      reporter_.error(e.at,
                      fmt::format("'{}' is given twice in this move", kChannels[e.output].name));
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
void RaspblockLowering::interpolate(Location at, ExactMs start, ExactMs t, std::uint64_t n,
                                    Easing ease, const std::map<std::size_t, int>& targets) {
  // The move on the timeline first (an output without a known start jumps: a flat segment at
  // its target); the packets then sample each output's segment.
  std::map<std::size_t, Segment> curve;
  for (const auto& [c, end] : targets) {
    Segment seg;
    seg.kind = ease.is_linear() ? CurveKind::Linear : CurveKind::Eased;
    seg.easing = ease;
    seg.start = start;
    seg.end = start + t;
    seg.from = pos_[c] ? *pos_[c] : end;
    seg.to = end;
    seg.at = at;
    curve[c] = seg;
    timeline_.add(c, seg);
  }
  for (std::uint64_t k = 1; k <= n && !full_; ++k) {
    const auto parts = static_cast<std::int64_t>(n);
    const auto done = static_cast<std::int64_t>(k);
    const ExactMs send = start + t * ExactMs::ratio(done - 1, parts);
    // The position k/n of the way through the move, sent at (k-1)/n of its time.
    const double when = (start + t * ExactMs::ratio(done, parts)).value();
    std::array<std::optional<int>, kChannels.size()> next;
    for (const auto& [c, seg] : curve) {
      next[c] = k < n ? static_cast<int>(std::llround(seg.value(when))) : targets.at(c);
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
              raspblock::SingleServo{kChannels[c].index, static_cast<std::uint16_t>(*next[c])}, at);
      pos_[c] = next[c];
    }
  }
}

void RaspblockLowering::wait_step(const YamlNode& step, const YamlNode& value) {
  auto total = exact_time(value, "'wait'");
  if (!total) return;
  begin_step(false);
  advance(*total, step.location);
}

void RaspblockLowering::repeat_step(const YamlNode& step, const YamlNode& value) {
  const auto repeat = parse_repeat(step, value, reporter_);
  if (!repeat) return;
  for (long long i = 0; i < repeat->times && !full_; ++i) {
    const std::size_t errors_before = reporter_.errors_reported();
    const ExactMs t0 = now_;
    const std::size_t p0 = packets_.size();
    run_steps(*repeat->body, "'do'");
    // Further passes would only repeat the same mistakes (and nested repeats never end).
    if (reporter_.errors_reported() > errors_before || full_) break;
    if (i > 0) continue;
    // After one pass the whole repeat's length is known: one that cannot fit fails here,
    // unexpanded (repeat 65535 nested six deep would otherwise run for hours).
    const auto rest = static_cast<std::uint64_t>(repeat->times - 1);
    const double dt = (now_ - t0).value();
    const std::uint64_t dp = packets_.size() - p0;
    const double left = static_cast<double>(kRaspblockMaxStreamMs) - now_.value();
    if (dt > 0 && static_cast<double>(rest) * dt > left) {
      reporter_.error(step.location, "this repeat would make the stream last longer than 24 hours");
      full_ = true;
    } else if (dp > 0 && rest > (kRaspblockMaxPackets - packets_.size()) / dp) {
      reporter_.error(step.location,
                      fmt::format("this repeat would make the stream need more than {} packets; "
                                  "use a coarser 'resolution' or fewer repeats",
                                  grouped(kRaspblockMaxPackets)));
      full_ = true;
    }
  }
}

void RaspblockLowering::include_step(const YamlNode& value) {
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

}  // namespace seqc::compiler
