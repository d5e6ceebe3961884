// The Raspblock front end's own steps (drive, move of the gimbal and servos, eased, and wait)
// into packets on the stream, and its hooks into the shared walk (step_walk.hpp): how it holds
// for `at:`, repeats within the stream's limits and stops a drive around `together` tracks.
#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "compiler/targets/raspblock/raspblock_lowering_state.hpp"

namespace seqc::compiler {

const StepTable kRaspblockSteps = {
    {"drive", "move", "wait"},
    {"drive", "move"},
    {"drive", "move", "wait", "repeat", "include", "section", "together", "tempo", "meter", "time",
     "ease", "steps", "do", "with", "at"},
    "a step needs one of: drive, move, wait, repeat, include, section, together, tempo, meter",
    "'drive: {x: 10}' or 'wait: 1s'",
    "spin.yaml",
    "'together: {wheels: [...], camera: [...]}'",
    [](const std::string& path, const std::string& reason) {
      return "cannot read included file '" + path + "': " + reason;
    },
};

void RaspblockLowering::own_step(const YamlNode& verb, const YamlNode& step) {
  if (verb.scalar == "wait") {
    if (reporter_.check_keys(step, {"wait", "at"}, "in a wait step") && apply_at(step)) {
      wait_step(step, *step.find("wait"));
    }
    return;
  }
  const YamlNode* drive = step.find("drive");
  const YamlNode* move = step.find("move");
  if (reporter_.check_keys(step, {"drive", "move", "time", "ease", "steps", "at"},
                           drive != nullptr && move != nullptr
                               ? "in a drive-and-move step"
                               : (drive ? "in a drive step" : "in a move step")) &&
      apply_at(step)) {
    motion_step(step, drive, move);
  }
}

bool RaspblockLowering::hold_until(ExactMs target, const YamlNode& at) {
  // A drive lasts for its step, not until the next one starts.
  begin_step(false);
  advance(target - now_, at.location);
  return true;
}

// After one pass the whole repeat's length is known: one that cannot fit fails there,
// unexpanded (repeat 65535 nested six deep would otherwise run for hours).
class RaspblockRepeatBudget final : public StepWalker::RepeatBudget {
 public:
  RaspblockRepeatBudget(RaspblockLowering& car, const YamlNode& step, long long times)
      : car_(car), step_(step), times_(times) {}
  bool before_pass(long long /*pass*/) override {
    t0_ = car_.now_;
    p0_ = car_.packets_.size();
    return true;
  }
  bool after_pass(long long pass) override {
    if (car_.full_) return false;
    if (pass > 0) return true;
    const auto rest = static_cast<std::uint64_t>(times_ - 1);
    const double dt = (car_.now_ - t0_).value();
    const std::uint64_t dp = car_.packets_.size() - p0_;
    const double left = static_cast<double>(kRaspblockMaxStreamMs) - car_.now_.value();
    if (dt > 0 && static_cast<double>(rest) * dt > left) {
      car_.reporter_.error(step_.location,
                           "this repeat would make the stream last longer than 24 hours");
      car_.full_ = true;
    } else if (dp > 0 && rest > (kRaspblockMaxPackets - car_.packets_.size()) / dp) {
      car_.reporter_.error(step_.location,
                           fmt::format("this repeat would make the stream need more than {} "
                                       "packets; use a coarser 'resolution' or fewer repeats",
                                       grouped(kRaspblockMaxPackets)));
      car_.full_ = true;
    }
    return !car_.full_;
  }

 private:
  RaspblockLowering& car_;
  const YamlNode& step_;
  long long times_;
  ExactMs t0_;
  std::size_t p0_ = 0;
};

std::unique_ptr<StepWalker::RepeatBudget> RaspblockLowering::repeat_budget(const YamlNode& step,
                                                                           long long times) {
  return std::make_unique<RaspblockRepeatBudget>(*this, step, times);
}

// The block is a step that does not drive: a drive before it has lasted its time. The drive a
// track ends with (one track drives, at most) lasts for its step, so it stops where that track
// ends, unless the block ends there too (then the step after the block may take over its
// speeds at the same instant).
class RaspblockBlockRun final : public StepWalker::BlockRun {
 public:
  explicit RaspblockBlockRun(RaspblockLowering& car) : car_(car) { car_.begin_step(false); }
  void track_ends() override {
    if (car_.stop_due_) drive_ends_ = {car_.now_, car_.last_drive_at_};
    car_.stop_due_ = false;
  }
  void block_ends(ExactMs /*start*/, ExactMs longest) override {
    if (!drive_ends_) return;
    if (drive_ends_->first < longest) {
      car_.emit_at(drive_ends_->first, raspblock::Rocker{0, 0, 0}, drive_ends_->second);
    } else {
      car_.stop_due_ = true;
      car_.last_drive_at_ = drive_ends_->second;
    }
  }

 private:
  RaspblockLowering& car_;
  std::optional<std::pair<ExactMs, Location>> drive_ends_;
};

std::unique_ptr<StepWalker::BlockRun> RaspblockLowering::block_run(const YamlNode& /*step*/) {
  return std::make_unique<RaspblockBlockRun>(*this);
}

bool RaspblockLowering::claim(const std::map<std::size_t, int>& targets, bool drives, Location at) {
  static constexpr std::string_view kOneTrack =
      "an output may move in one track of a "
      "'together' only";
  bool ok = true;
  // Pan and tilt are outputs of their own: the gimbal packets of two tracks are merged by
  // instant once the walk ends (merge_gimbal_packets).
  for (const auto& [c, units] : targets) {
    ok = claims_.claim(c, "'" + std::string(kChannels[c].name) + "'", "moves", kOneTrack, at,
                       reporter_) &&
         ok;
  }
  if (drives) {
    ok = claims_.claim(kChannels.size(), "the car", "drives",
                       "the drive belongs to one track of a 'together' only", at, reporter_) &&
         ok;
  }
  return ok;
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

  if (!claim(targets, drive.has_value(), step.location)) return;
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
  // In a track, another track may set the other at the same instant: merge_gimbal_packets
  // checks it in time order.
  if (ok && pan != tilt && !claims_.in_block()) {
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
    // The packets sample the curve, but the servo follows it between them too, and simulate,
    // plot and preview draw it whole: an ease past the range is a mistake in the file.
    if (!check_curve_limits(seg, kChannels[c].name, kChannels[c].min, kChannels[c].max, at,
                            std::nullopt, reporter_)) {
      return;
    }
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
    // A gimbal packet when pan or tilt changes; the value of the one not set here is what it
    // has when the walk ends (merge_gimbal_packets), which another track may set meanwhile.
    const bool pan_changes = next[kPan] && pos_[kPan] != next[kPan];
    const bool tilt_changes = next[kTilt] && pos_[kTilt] != next[kTilt];
    if (pan_changes || tilt_changes) {
      const int h = next[kPan].value_or(pos_[kPan].value_or(kHome));
      const int v = next[kTilt].value_or(pos_[kTilt].value_or(kHome));
      const std::size_t before = packets_.size();
      emit_at(send,
              raspblock::GimbalServos{static_cast<std::uint16_t>(h), static_cast<std::uint16_t>(v)},
              at);
      if (packets_.size() > before) {
        gimbal_sets_[before] = {pan_changes ? next[kPan] : std::nullopt,
                                tilt_changes ? next[kTilt] : std::nullopt};
      }
      if (next[kPan]) pos_[kPan] = next[kPan];
      if (next[kTilt]) pos_[kTilt] = next[kTilt];
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

}  // namespace seqc::compiler
