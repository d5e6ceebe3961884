// The servo-controller front end: files, step lists and the structural steps. Motion steps
// (move, wait, through) are in servo_motion.cpp; fitting the finished timeline into actions is
// compiler/fitting/.
#include "compiler/targets/servo_controller/servo_lowering.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string_view>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "compiler/fitting/fitter.hpp"
#include "base/units.hpp"
#include "compiler/frontend/step_parts.hpp"
#include "compiler/targets/servo_controller/servo_lowering_state.hpp"
#include "protocol/group_download.hpp"

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

ServoLowering::ServoLowering(const Robot& robot, FileLoader& loader, Reporter& reporter)
    : StepWalker(loader, reporter, kServoSteps, robot.home_servos, robot.info.servos.size()),
      robot_(robot),
      pos_(robot.info.servos.size()) {}

ServoProgram ServoLowering::run(const LoadedFile& main, const ServoFitting& fitting) {
  fitting_ = fitting;
  run_file(main, true);
  ServoProgram program;
  program.robot = robot_.info;
  program.group_capacity = capacity();
  finish(program);
  return program;
}

void ServoLowering::finish(ServoProgram& program) {
  timeline_.end = now_;
  // A file with mistakes makes no program: fitting it would only cost time (a long, slow curve
  // took seconds; found by the check fuzzer).
  if (reporter_.errors_reported() > 0) return;
  refit_lines();
  if (over_budget_at_) {
    // Already more actions than a group holds before fitting (each step needs at least its
    // count): fitting tens of thousands of steps would only cost time.
    reporter_.error(*over_budget_at_, "the sequence needs at least " +
                                          std::to_string(min_actions_) + "/" +
                                          std::to_string(capacity()) + " actions; " +
                                          group_capacity_text(robot_.profile));
    return;
  }
  FitOptions fit_options;
  fit_options.model = robot_.controller;
  fit_options.free_end_points = fitting_.free_end_points;
  for (const ServoInfo& s : robot_.info.servos) fit_options.limits.push_back({s.min, s.max});
  // A board clock e fast plays a board millisecond in 1 / (1 + e) host ms: the author's
  // instants are stretched by (1 + e) before the fit rounds each boundary once, so the error
  // never accumulates action by action.
  FitResult fit =
      fitting_.clock_ppm == 0
          ? fit_timeline(timeline_, fit_options)
          : fit_timeline(timeline_.stretched(1000000 + std::int64_t{fitting_.clock_ppm}, 1000000),
                         fit_options);
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
  // The tip's own error on the lines, from the actions as they were fitted (all of them: a
  // group cut at its capacity is an error already).
  for (const LineRecord& line : lines_) {
    if (needed > capacity()) break;
    std::array<std::size_t, 4> joints{};
    std::copy_n(line.servos.begin(), 4, joints.begin());
    const backend::TipLineError e = backend::measure_tip_line(
        line.request, joints, fit.actions, 1 + static_cast<double>(fitting_.clock_ppm) / 1e6);
    // Under a clock scale the line's boundaries are rounded again on the board's clock, which
    // moves the tip along the line by a fraction of a millisecond's travel: that is the scale's
    // (the budget line shows it), not another track's, so only an unscaled fit warns.
    if (fitting_.clock_ppm == 0 && e.mm > line.request.tolerance_mm + 1e-9) {
      reporter_.warning(
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
  program.controller = fit_options.model;
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
                       {"robot", "music", "tempo", "meter", "resolution", "tolerance", "poses",
                        "sections", "sequence", "name", "description"},
                       "at the top level");
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
    const bool keys_ok = reporter_.check_keys(
        step, {"move", "time", "ease", "steps", "tolerance", "elbow", "path", "at"},
        "in a move step");
    if (apply_at(step)) move_step(step, value, keys_ok);
  } else if (name == "wait") {
    reporter_.check_keys(step, {"wait", "at"}, "in a wait step");
    if (apply_at(step)) wait_step(step, value);
  } else if (name == "through") {
    reporter_.check_keys(step, {"through", "tolerance", "at"}, "in a through step");
    if (apply_at(step)) through_step(step, value);
  } else if (name == "mirror") {
    if (reporter_.check_keys(step, {"mirror", "at"}, "in a mirror step") && apply_at(step)) {
      mirror_step(step, value);
    }
  } else {
    tolerance_step(value);
  }
}

bool ServoLowering::hold_until(ExactMs target, const YamlNode& at) {
  const bool known = std::any_of(pos_.begin(), pos_.end(), [](auto& p) { return p.has_value(); });
  // In a track another track may be moving meanwhile (block_run checks that one does).
  if (!known && !claims_.in_block()) {
    reporter_.error(at.location,
                    "nothing to hold until 'at': no servo has a position yet; start with a move");
    return false;
  }
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
  ServoRepeatBudget(std::uint64_t& min_actions, bool& truncated, std::size_t capacity,
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
  std::size_t capacity_;
  long long times_;
  std::uint64_t before_ = 0;
  std::uint64_t per_pass_ = 0;
};

std::unique_ptr<StepWalker::RepeatBudget> ServoLowering::repeat_budget(const YamlNode& /*step*/,
                                                                       long long times) {
  return std::make_unique<ServoRepeatBudget>(min_actions_, truncated_, capacity(), times);
}

// The block needs as many actions as its busiest track; and when nothing had a position
// before it, one track must move at its start, or the controller has nothing to send.
class ServoBlockRun final : public StepWalker::BlockRun {
 public:
  ServoBlockRun(ServoLowering& lowering, const YamlNode& step, std::uint64_t& min_actions,
                bool known, bool outer, std::size_t errors_before)
      : lowering_(lowering),
        step_(step),
        min_actions_(min_actions),
        before_(min_actions),
        known_(known),
        outer_(outer),
        errors_before_(errors_before) {}
  void track_begins() override { min_actions_ = before_; }
  void track_ends() override { most_ = std::max(most_, min_actions_ - before_); }
  void block_ends(ExactMs start, ExactMs longest) override {
    min_actions_ = before_ + most_;
    lowering_.check_block_start(step_, start, longest, known_ || outer_, errors_before_);
  }

 private:
  ServoLowering& lowering_;
  const YamlNode& step_;
  std::uint64_t& min_actions_;
  std::uint64_t before_;
  std::uint64_t most_ = 0;
  bool known_, outer_;
  std::size_t errors_before_;
};

std::unique_ptr<StepWalker::BlockRun> ServoLowering::block_run(const YamlNode& step) {
  const bool known = std::any_of(pos_.begin(), pos_.end(), [](auto& p) { return p.has_value(); });
  return std::make_unique<ServoBlockRun>(*this, step, min_actions_, known, claims_.in_block(),
                                         reporter_.errors_reported());
}

void ServoLowering::check_block_start(const YamlNode& step, ExactMs start, ExactMs longest,
                                      bool held, std::size_t errors_before) {
  // A track may wait (or start `at:` later) while another moves.
  if (held || reporter_.errors_reported() > errors_before) return;
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

void ServoLowering::tolerance_step(const YamlNode& value) {
  if (auto t = parse_tolerance(value)) lists_.back().tolerance = t;
}

ServoProgram lower_servo_program(const Robot& robot, const LoadedFile& main, FileLoader& loader,
                                 Reporter& reporter, const ServoFitting& fitting) {
  return ServoLowering(robot, loader, reporter).run(main, fitting);
}

}  // namespace seqc::compiler
