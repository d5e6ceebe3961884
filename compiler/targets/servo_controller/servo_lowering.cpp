// The servo-controller target: the walk's files, step lists and structural steps, and the
// program made of the fitted actions. Motion steps (move, wait, through) are in
// servo_motion.cpp; fitting the finished timeline into actions is compiler/fitting/, which the
// driver runs between the two.
#include "compiler/targets/servo_controller/servo_lowering.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string_view>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "base/units.hpp"
#include "compiler/fitting/fitter.hpp"
#include "compiler/frontend/key_tables.hpp"
#include "compiler/frontend/step_parts.hpp"
#include "compiler/targets/servo_controller/group_budget.hpp"
#include "compiler/targets/servo_controller/servo_lowering_state.hpp"
#include "protocol/lsc/group_download.hpp"

namespace seqc::compiler {
namespace {

std::uint64_t saturating_add(std::uint64_t a, std::uint64_t b) {
  return a > std::numeric_limits<std::uint64_t>::max() - b
             ? std::numeric_limits<std::uint64_t>::max()
             : a + b;
}

}  // namespace

const StepTable kServoSteps = {
    {"move", "wait", "through", "mirror", "tolerance"},
    {},
    {"move", "wait", "through", "repeat", "include", "mirror", "section", "together", "tempo",
     "meter", "tolerance", "time", "ease", "steps", "elbow", "path", "do", "with", "at"},
    "a step needs one of: move, wait, through, repeat, include, mirror, section, together, "
    "tempo, meter, tolerance",
    "'move: home' or 'wait: 1s'",
    "wave.yaml",
    "'together: {arm: [...], claw: [...]}'",
    [](const std::string&, const std::string& reason) { return "cannot include it: " + reason; },
};

const StepTable& servo_step_table() { return kServoSteps; }

ServoLowering::ServoLowering(const Robot& robot, FileLoader& loader, Reporter& reporter,
                             std::size_t groups, const RobotStart& start)
    : StepWalker(loader, reporter, kServoSteps, robot.home_servos, robot.info.servos.size()),
      groups_(std::max<std::size_t>(1, groups)),
      robot_(robot),
      start_(start),
      pos_(robot.info.servos.size()) {}

ServoWalk ServoLowering::run(const LoadedFile& main) {
  run_file(main, true);
  timeline_.end = now_;
  // The lines are fitted again only once every track is walked, and only in a file without
  // mistakes (ready_to_fit() fits nothing else).
  if (reporter_.errors_reported() == 0 && !lines_.empty()) {
    // What the file wrote, kept for the views where a line takes other servos' curves.
    auto written = std::make_shared<const Timeline>(timeline_);
    const std::size_t replaced = replaced_curves_;
    refit_lines();
    if (replaced_curves_ > replaced) timeline_.written = std::move(written);
  }
  check_tip_depth();
  ServoWalk walk;
  walk.min_actions = min_actions_;
  walk.truncated = truncated_;
  walk.over_budget_at = over_budget_at_;
  walk.over_budget_notes = over_budget_notes_;
  walk.sequence_at = sequence_at_;
  walk.capacity = capacity();
  walk.groups = groups_;
  walk.over_budget_time = over_budget_time_;
  walk.performances = std::move(performances_);
  walk.start_reads = start_reads_;
  for (const LineRecord& line : lines_) {
    ServoTipLine l{line.request, {}, line.path_at};
    std::copy_n(line.servos.begin(), 4, l.joints.begin());
    walk.lines.push_back(std::move(l));
  }
  walk.timeline = std::move(timeline_);
  return walk;
}

ServoWalk walk_servo_file(const Robot& robot, const LoadedFile& main, FileLoader& loader,
                          Reporter& reporter, std::size_t groups, const RobotStart& start,
                          StepTimes* times) {
  ServoLowering lowering(robot, loader, reporter, groups, start);
  lowering.record_times(times);
  return lowering.run(main);
}

bool ready_to_fit(const ServoWalk& walk, const Robot& robot, Reporter& reporter) {
  if (walk.over_budget_at) {
    // The walk stopped there (its count includes the passes left of the repeats it was in),
    // whatever mistakes came before: the steps after it were never read.
    std::string message = budget_text(robot, walk.capacity, walk.groups, walk.min_actions, true);
    if (walk.over_budget_time)
      message += when_text(walk.timeline.tempo_map, *walk.over_budget_time);
    std::vector<Reporter::Note> notes = walk.over_budget_notes;
    if (const auto hint = chain_hint(walk)) notes.push_back(*hint);
    reporter.error_with_notes(*walk.over_budget_at, message, notes);
    return false;
  }
  return reporter.errors_reported() == 0;
}

FitOptions servo_fit_options(const Robot& robot, bool free_end_points) {
  FitOptions options;
  options.model = robot.controller;
  options.free_end_points = free_end_points;
  for (const ServoInfo& s : robot.info.servos) options.limits.push_back({s.min, s.max});
  return options;
}

namespace {

// One warning per curve: its worst miss, naming every servo that misses it (each 20ms action
// that falls short is a shortfall of its own, the same fact many times over).
void warn_shortfalls(const RobotInfo& robot, const ServoWalk& walk, const FitResult& fit,
                     Timeline& timeline, Reporter& reporter) {
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
        first.where.file != kNoFile ? first.where : walk.sequence_at.value_or(Location{0, 1, 1});
    std::string who;
    for (std::size_t servo : servos) {
      who += (who.empty() ? "'" : ", '") + robot.servos[servo].name + "'";
    }
    const std::string message =
        servos.size() == 1
            ? "even 20ms actions cannot keep " + who + " within " + format_units(worst.tolerance) +
                  " of this curve: it is " + format_units(worst.error) + " off at " +
                  format_seconds(worst.at_ms)
            : "even 20ms actions cannot keep servos " + who + " within " +
                  format_units(worst.tolerance) + " of this curve: up to " +
                  format_units(worst.error) + " off ('" + robot.servos[worst.servo].name + "' at " +
                  format_seconds(worst.at_ms) + ")";
    reporter.warning(where, message);
    for (std::size_t servo : servos) {
      timeline.warnings.push_back({static_cast<double>(worst.at_ms), servo, message});
    }
  }
}

// A first move from an unknown position that other tracks' actions cut is sent only with the
// action that ends it (Segment::from_unknown): the servo holds until then and covers the whole
// way in that action's time. Said once per servo, with the far end of its limits checked
// against max_speed over the time it really gets.
void warn_late_first_moves(const RobotInfo& robot, const Timeline& timeline,
                           const std::vector<FittedAction>& actions, Reporter& reporter) {
  for (std::size_t servo = 0; servo < robot.servos.size(); ++servo) {
    if (timeline.count(servo) == 0) continue;
    const Segment seg = timeline.segment(servo, 0);
    if (!seg.from_unknown) continue;
    const auto named = std::find_if(actions.begin(), actions.end(), [&](const FittedAction& a) {
      return std::any_of(a.targets.begin(), a.targets.end(),
                         [&](const FittedTarget& t) { return t.servo == servo; });
    });
    if (named == actions.end() || static_cast<std::int64_t>(named->start_ms) <= seg.start.round()) {
      continue;
    }
    const ServoInfo& info = robot.servos[servo];
    const int target = static_cast<int>(std::lround(seg.to));
    std::string message = fmt::format(
        "'{}' has no known position before this move, and other tracks' actions cut it: it "
        "holds until {} and reaches {} in {} (the action that ends the move), not in {}",
        info.name, format_seconds(named->start_ms), target, format_seconds(named->time_ms),
        format_seconds(static_cast<std::uint64_t>(seg.end.round() - seg.start.round())));
    if (const std::optional<FarEnd> far = far_end(info, target);
        far && far->needs_ms > named->time_ms + 1e-9) {
      message += fmt::format("; from {} it needs {:g} s at max_speed {:.0f}/s", far->from,
                             std::ceil(far->needs_ms / 10 - 1e-9) / 100, *info.max_speed);
    }
    reporter.warning(seg.at, message +
                                 "; give it a position before this, or start its move "
                                 "with the others");
  }
}

}  // namespace

ServoProgram servo_program(const Robot& robot, ServoWalk walk, const FitResult& fit_result,
                           std::int32_t clock_ppm, Reporter& reporter) {
  ServoProgram program;
  program.robot = robot.info;
  program.group_capacity = walk.capacity;
  program.groups = walk.groups;
  program.start_reads = walk.start_reads;
  std::vector<FittedAction> actions = fit_result.actions;
  const std::uint64_t needed = std::max<std::uint64_t>(actions.size(), walk.min_actions);
  const std::uint64_t budget = std::uint64_t{walk.capacity} * walk.groups;
  if (needed > budget) {
    const bool past = actions.size() > budget;
    const FittedAction& first_out = past ? actions[budget] : actions.back();
    std::string message = budget_text(robot, walk.capacity, walk.groups, needed, walk.truncated);
    std::vector<Reporter::Note> notes;
    if (past) {
      // The action's start on the board's clock, back on the music's.
      const ExactMs host = ExactMs(std::int64_t{first_out.start_ms}) /
                           ExactMs::ratio(1000000 + std::int64_t{clock_ppm}, 1000000);
      message += when_text(walk.timeline.tempo_map, host);
      notes = walk.performances.at(host);
    }
    if (const auto hint = chain_hint(walk)) notes.push_back(*hint);
    reporter.error_with_notes(first_out.source, message, notes);
    actions.resize(std::min<std::size_t>(actions.size(), budget));
  } else if (actions.empty() && walk.sequence_at && reporter.errors_reported() == 0) {
    reporter.error(*walk.sequence_at, "the sequence makes no actions; a group needs at least one");
  } else if (walk.sequence_at && reporter.errors_reported() == 0 &&
             std::all_of(actions.begin(), actions.end(),
                         [](const FittedAction& a) { return a.targets.empty(); })) {
    // Rests alone: the robot would only stand where it stands.
    reporter.error(*walk.sequence_at, "the sequence only rests: it moves no servo; add a move");
  }
  warn_shortfalls(robot.info, walk, fit_result, walk.timeline, reporter);
  warn_late_first_moves(robot.info, walk.timeline, actions, reporter);
  for (const FittedAction& a : actions) {
    Keyframe k;
    k.start_ms = a.start_ms;
    k.time_ms = static_cast<std::uint16_t>(a.time_ms);
    k.source = a.source;
    for (const FittedTarget& t : a.targets) {
      k.targets.push_back(
          {robot.info.servos[t.servo].id, static_cast<std::uint16_t>(std::max(0, t.position))});
    }
    std::sort(k.targets.begin(), k.targets.end(),
              [](const lsc::ServoTarget& x, const lsc::ServoTarget& y) { return x.id < y.id; });
    program.keyframes.push_back(std::move(k));
  }
  // The tip's own error on the lines, from the actions as they were fitted (all of them: a
  // group cut at its capacity is an error already).
  for (const ServoTipLine& line : walk.lines) {
    if (needed > walk.capacity) break;
    const compiler::TipLineError e = compiler::measure_tip_line(
        line.request, line.joints, actions, 1 + static_cast<double>(clock_ppm) / 1e6);
    // Under a clock scale the line's boundaries are rounded again on the board's clock, which
    // moves the tip along the line by a fraction of a millisecond's travel: that is the scale's
    // (the budget line shows it), not another track's, so only an unscaled fit warns.
    if (clock_ppm == 0 && e.mm > line.request.tolerance_mm + 1e-9) {
      reporter.warning(
          line.path_at,
          fmt::format("the tip strays up to {:.2f} mm from this line (at {}), more than its "
                      "tolerance of {:g}mm: other tracks' moves during it cut the joints' "
                      "actions where the line cannot choose their targets; keep the other "
                      "tracks straight while it runs, or give it its own stretch of time",
                      e.mm, format_seconds(e.at_ms), line.request.tolerance_mm));
    }
    if (!program.tip_error_mm || e.mm > *program.tip_error_mm) {
      program.tip_error_mm = e.mm;
      program.tip_error_at_ms = e.at_ms;
    }
  }
  program.controller = robot.controller;
  program.fit_error = fit_result.max_error;
  program.fit_error_at_ms = fit_result.max_error_at_ms;
  program.fit_error_servo = robot.info.servos.empty()
                                ? std::string()
                                : robot.info.servos[fit_result.max_error_servo].name;
  program.timeline = std::move(walk.timeline);
  return program;
}

// ---- files and scopes -----------------------------------------------------------------------

void ServoLowering::run_file(const LoadedFile& f, bool is_main) {
  const YamlNode* map = file_root(f, reporter_);
  if (map == nullptr) return;
  const YamlNode& root = *map;
  if (!is_main && !is_choreography(f)) {
    // An include with no 'sequence' may be any file: its one error names none of its keys.
    find_sequence(root, reporter_);
    return;
  }
  reporter_.check_keys(root, kServoFileKeys, "at the top level");
  reporter_.check_free_text(root);
  if (!is_main && !check_included_robot(root, robot_.info.profile, reporter_)) {
    return;  // its steps would only add errors about servos this robot lacks
  }
  FileScope& scope = scope_for(f);
  const YamlNode* sequence = find_sequence(root, reporter_);
  if (sequence == nullptr) return;
  if (is_main) sequence_at_ = sequence->location;
  run_sequence(root, scope, *sequence, is_main);
}

FileScope& ServoLowering::scope_for(const LoadedFile& f) {
  auto [scope, fresh] = scopes_.open(f, reporter_);
  if (!fresh) return scope;
  const YamlNode& root = *f.root;
  scopes_.push(scope);  // so this file's tempo, meter, groups and poses apply while it is read
  if (const YamlNode* g = root.find("groups")) parse_groups(*g, scope);
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
  if (const YamlNode* s = root.find("sections")) read_sections(*s, scope, reporter_);
  scopes_.pop();
  return scope;
}

// ---- the walk's hooks ------------------------------------------------------------------------

bool ServoLowering::is_verb(std::string_view key, const YamlNode& step) const {
  if (key == "tolerance") return step.entries.size() == 1;
  return StepWalker::is_verb(key, step);
}

void ServoLowering::own_step(const YamlNode& verb, const YamlNode& step) {
  const std::string& name = verb.scalar;
  const YamlNode& value = *step.find(name);
  if (name == "move") {
    // Every mistake of the step is reported, so unknown keys do not stop the checks.
    const bool keys_ok = reporter_.check_keys(step, kMoveStepKeys, "in a move step");
    if (apply_at(step)) move_step(step, value, keys_ok);
  } else if (name == "wait") {
    reporter_.check_keys(step, kWaitStepKeys, "in a wait step");
    if (apply_at(step)) wait_step(step, value);
  } else if (name == "through") {
    reporter_.check_keys(step, kThroughStepKeys, "in a through step");
    if (apply_at(step)) through_step(step, value);
  } else if (name == "mirror") {
    if (reporter_.check_keys(step, kMirrorStepKeys, "in a mirror step") && apply_at(step)) {
      mirror_step(step, value);
    }
  } else {
    tolerance_step(value);
  }
}

bool ServoLowering::hold_until(ExactMs target, const YamlNode& at) {
  // Before the first move this is an opening rest: the servos stay where they stand.
  // The hold is at least one action per 30 s (a far position must not reach the fitter).
  const auto gap = static_cast<std::uint64_t>((target - now_).value());
  count_actions(std::max<std::uint64_t>(1, (gap + lsc::kMaxActionMs - 1) / lsc::kMaxActionMs),
                at.location);
  now_ = target;
  return true;
}

// Each pass adds at least its actions to the count; once the count is past the group's
// budget, the passes left are counted, not expanded.
class ServoRepeatBudget final : public StepWalker::RepeatBudget {
 public:
  ServoRepeatBudget(std::uint64_t& min_actions, bool& truncated, std::uint64_t capacity,
                    long long times)
      : min_actions_(min_actions), truncated_(truncated), capacity_(capacity), times_(times) {}
  bool before_pass(long long pass) override {
    if (pass > 0 && min_actions_ > capacity_) {  // already too long: count, do not expand
      const auto rest = static_cast<std::uint64_t>(times_ - pass);
      min_actions_ = saturating_add(min_actions_, per_pass_ > 0 && rest > UINT64_MAX / per_pass_
                                                      ? UINT64_MAX
                                                      : rest * per_pass_);
      truncated_ = true;
      return false;
    }
    before_ = min_actions_;
    return true;
  }
  bool after_pass(long long /*pass*/) override {
    per_pass_ = min_actions_ - before_;
    // A pass that makes no actions would make none again: 65535 nested six deep would never
    // end (found by hostile_bench).
    return per_pass_ > 0;
  }

 private:
  std::uint64_t& min_actions_;
  bool& truncated_;
  std::uint64_t capacity_;
  long long times_;
  std::uint64_t before_ = 0;
  std::uint64_t per_pass_ = 0;
};

std::unique_ptr<StepWalker::RepeatBudget> ServoLowering::repeat_budget(const YamlNode& /*step*/,
                                                                       long long times) {
  return std::make_unique<ServoRepeatBudget>(min_actions_, truncated_, budget(), times);
}

// The block needs as many actions as its busiest track. Tracks that start later (or a block
// in which none moves at its start) rest meanwhile: their servos stay where they stand.
class ServoBlockRun final : public StepWalker::BlockRun {
 public:
  explicit ServoBlockRun(std::uint64_t& min_actions)
      : min_actions_(min_actions), before_(min_actions) {}
  void track_begins() override { min_actions_ = before_; }
  void track_ends() override { most_ = std::max(most_, min_actions_ - before_); }
  void block_ends(ExactMs /*start*/, ExactMs /*longest*/) override {
    min_actions_ = before_ + most_;
  }

 private:
  std::uint64_t& min_actions_;
  std::uint64_t before_;
  std::uint64_t most_ = 0;
};

std::unique_ptr<StepWalker::BlockRun> ServoLowering::block_run(const YamlNode& /*step*/) {
  return std::make_unique<ServoBlockRun>(min_actions_);
}

void ServoLowering::mirror_step(const YamlNode& step, const YamlNode& body) {
  if (!robot_.has_mirror_table) {
    reporter_.error(step.location,
                    "'mirror' needs a mirror table in the robot section, e.g. "
                    "'mirror: {left_arm: right_arm}' under 'robot:'");
    return;
  }
  if (!open_block(step.location, "mirror")) return;
  mirrored_ = !mirrored_;
  run_steps(body, "'mirror'");
  mirrored_ = !mirrored_;
  close_block();
}

void ServoLowering::tolerance_step(const YamlNode& value) {
  if (auto t = parse_tolerance(value)) lists_.back().tolerance = t;
}

}  // namespace seqc::compiler
