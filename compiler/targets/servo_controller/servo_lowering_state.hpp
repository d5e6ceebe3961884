// The servo-controller front end's state while it walks a file's steps (private to
// servo_lowering.cpp, which reads files and supplies the shared walk's hooks, and
// servo_motion.cpp, which turns move, wait and through steps into timeline segments, with their
// checks in servo_motion_checks.cpp, and servo_tip.cpp / servo_tip_line.cpp for the arm's tip). The
// walk itself (lists, repeat, include, sections, together, at, tempo, meter) is StepWalker's
// (step_walk.hpp).
//
// Time is exact (ExactMs): each step list remembers when it started (for `at:`) and its
// tolerance override; beats and bars go through the timeline's tempo map. A `together` block
// runs each track from the block's start, and a servo may move in one track of each block only.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "compiler/frontend/file_loader.hpp"
#include "compiler/frontend/positions.hpp"
#include "compiler/frontend/profiles.hpp"
#include "compiler/frontend/reporter.hpp"
#include "compiler/frontend/robot_section.hpp"
#include "compiler/frontend/scope_chain.hpp"
#include "compiler/frontend/step_walk.hpp"
#include "compiler/program/program.hpp"
#include "compiler/targets/servo_controller/servo_lowering.hpp"
#include "compiler/targets/servo_controller/tip_depth.hpp"
#include "compiler/targets/servo_controller/tip_line.hpp"
#include "compiler/timeline/exact_time.hpp"
#include "compiler/timeline/timeline.hpp"

namespace seqc::compiler {

// Where a servo may be when a group starts and it has no known position: the end of its limits
// farthest from `target`, and how long max_speed needs from there (nullopt without max_speed).
struct FarEnd {
  int from = 0;
  double needs_ms = 0;
};
std::optional<FarEnd> far_end(const ServoInfo& info, int target);

class ServoLowering final : public StepWalker {
 public:
  ServoLowering(const Robot& robot, FileLoader& loader, Reporter& reporter, std::size_t groups,
                const RobotStart& start);
  ServoWalk run(const LoadedFile& main);

 private:
  // ---- files and the walk's hooks (servo_lowering.cpp) --------------------------------------
  void run_file(const LoadedFile& f, bool is_main) override;
  FileScope& scope_for(const LoadedFile& f);
  // move, wait, through, mirror and tolerance.
  void own_step(const YamlNode& verb, const YamlNode& step) override;
  // 'tolerance' is a verb only on its own: on a move or through it is a setting.
  bool is_verb(std::string_view key, const YamlNode& step) const override;
  bool hold_until(ExactMs target, const YamlNode& at) override;
  bool stopped() const override { return over_budget_at_.has_value(); }
  std::unique_ptr<RepeatBudget> repeat_budget(const YamlNode& step, long long times) override;
  std::unique_ptr<BlockRun> block_run(const YamlNode& step) override;
  void mirror_step(const YamlNode& step, const YamlNode& body);
  void tolerance_step(const YamlNode& value);

  // ---- values (servo_lowering.cpp) ----------------------------------------------------------
  // A map of `servo: position` entries; a group's name gives each of its servos the value.
  std::vector<PositionEntry> parse_positions(const YamlNode& map, const std::string& where);
  // A file's `groups` into `scope` (its poses may name them, so they are read first).
  void parse_groups(const YamlNode& groups, FileScope& scope);
  ScopeChain::ParseEntries entries_parser();
  double absolute_units(const PositionEntry& e, std::size_t target, bool reflect) const;
  bool check_limits(const PositionEntry& e, std::size_t target, double units, std::string how,
                    std::optional<Reporter::Note> note = {});
  // A time value as exact milliseconds (ms, s, or beats and bars counted through the tempo map
  // from now).
  std::optional<ExactMs> exact_time(const YamlNode& node, std::string_view what);
  // Device units of a tolerance ("1", "0.5deg"); nullopt after reporting.
  std::optional<double> parse_tolerance(const YamlNode& node);
  double tolerance() const;

  // ---- motion (servo_motion.cpp, servo_motion_checks.cpp)
  // ------------------------------------------------------------ `keys_ok`: false when the step has
  // an unknown key (then a missing 'time' is most likely that key misspelt, already reported).
  void move_step(const YamlNode& step, const YamlNode& target, bool keys_ok);
  // A move's `tip:` (servo_tip.cpp): appends to `entries` (the move's other servos) the joint
  // positions that put the claw's tip there, with the move's `pitch:` and the step's `elbow:`;
  // false after reporting.
  // `placed` gets the point, pitch and elbow it solved for (a `path: line` move's end).
  struct TipTarget {
    std::array<double, 3> point{};
    double pitch = 0;
    bool elbow_up = true;
    std::array<std::size_t, 4> joints{};  // base, shoulder, elbow, wrist servos
  };
  bool tip_entries(const YamlNode& step, const YamlNode& target,
                   std::vector<PositionEntry>& entries, TipTarget& placed);
  void wait_step(const YamlNode& step, const YamlNode& value);
  void through_step(const YamlNode& step, const YamlNode& waypoints);
  // The positions a move's entries reach, by servo (nullopt: not named), from the positions in
  // `targets` on entry; false if any entry was wrong (reported). `degrees` gets, for servos
  // whose entry was written in degrees, the distance in degrees as written (NaN otherwise).
  bool resolve_targets(const std::vector<PositionEntry>& entries,
                       const std::optional<Reporter::Note>& note,
                       std::vector<std::optional<int>>& targets, std::vector<double>& degrees);
  // Where `servo` stands before its first move, `e`, relative to it: its reading, or its home
  // with a note under RobotStart::assume_home; nullopt after reporting that it is unknown here.
  std::optional<int> standing(std::size_t servo, const PositionEntry& e,
                              const std::optional<Reporter::Note>& note);
  void add_segment(std::size_t servo, Segment segment);
  // One servo breaking its max_speed or max_accel on one segment, kept until the step ends so
  // the servos that break it alike get one warning.
  struct KinematicFinding {
    std::size_t servo = 0;
    bool speed = true;  // else acceleration
    bool curved = false;
    Location at;
    double start_ms = 0;
    std::optional<Reporter::Note> note;
    std::string moved, value, shape, limit;  // "100 in 2000ms", "400/s", " on this ...", "300/s"
    // A vertical curve's speed is its least within the tolerance: " within a tolerance of 1".
    std::string within;
  };
  // Speed and acceleration along a segment, from its exact derivative; what breaks a limit goes
  // to `findings`. `degrees`: the distance as written in degrees (NaN: in device units).
  void check_kinematics(std::size_t servo, const Segment& segment, double degrees,
                        const std::optional<Reporter::Note>& note,
                        std::vector<KinematicFinding>& findings);
  void report_kinematics(const std::vector<KinematicFinding>& findings);
  // A `path: line` move (servo_tip_line.cpp): the straight pieces of the joints that keep the tip
  // within `tolerance_mm` of the line from where it is to `placed`, and of the move's other
  // servos (`targets`, by servo) that keep them within `tolerance_units` of their eased curves,
  // added to the timeline from `start` to `end`; the final positions go to `pos_`. False after
  // reporting.
  bool tip_line(const YamlNode& step, const TipTarget& placed,
                const std::vector<std::optional<int>>& targets, ExactMs start, ExactMs end,
                const Easing& ease, double tolerance_mm, double tolerance_units,
                std::vector<KinematicFinding>& findings);
  // A `path: line` move as tip_line() fitted it, for refit_lines().
  struct LineRecord {
    compiler::TipLineRequest request;
    std::vector<std::size_t> servos;  // the joints (base, shoulder, elbow, wrist), then others
    std::vector<std::size_t> first;   // per servo, the index of its first piece in the timeline
    std::size_t pieces = 0;           // the line's actions, one piece per servo each
    std::vector<std::uint32_t> ends;  // each action's end, ms
    ExactMs start, end;
    double tolerance_units = 1;
    Location step_at, path_at;
  };
  // Each servo's pieces of the line fitted as `fit`.
  std::vector<std::vector<Segment>> line_pieces(const compiler::TipLineRequest& request,
                                                const compiler::TipLineResult& fit,
                                                const LineRecord& line) const;
  // Once every track is walked: fits again each line inside which other servos' segments begin
  // or end (the fitter ends every servo's action there), with those instants as boundaries of
  // the line's own actions and its end as it was, and with the curves other servos follow
  // within the line's time as its own other servos (else the fitter would cut the joints'
  // pieces where it fits them). Where no such actions keep the tolerance the line stays as it
  // was and servo_program() warns with the tip's true distance.
  void refit_lines();
  std::size_t replaced_curves_ = 0;  // other servos' curves refit_lines() took into lines
  // A group's first move of a servo may start anywhere in its limits: warns when `time` is too
  // short from the far end at max_speed. `targets`: the move's positions, by servo.
  void check_first_move(const std::vector<std::optional<int>>& targets, ExactMs time, Location at);
  // Limits along a curve that may overshoot its ends.
  bool check_overshoot(std::size_t servo, const Segment& segment, Location at,
                       const std::optional<Reporter::Note>& note);
  // A step from `start` to `end` that moved servos for which `moves` is true: kept when any is
  // one of the arm's joints, for check_tip_depth() (servo_tip.cpp). `tip_end`: its end was placed
  // by a `tip:`; `line_tolerance_mm`: a `path: line`'s tolerance.
  void record_arm_move(const std::function<bool(std::size_t)>& moves, ExactMs start, ExactMs end,
                       Location at, bool tip_end, double line_tolerance_mm);
  // Once every track is walked: the claw's tip against the table at every millisecond of every
  // move kept by record_arm_move() (tip_depth.hpp), one error per step that takes it below.
  void check_tip_depth();
  // Marks `servo` as moved by the running track; false after reporting a servo in two tracks.
  bool claim(std::size_t servo, Location at);
  void count_actions(std::uint64_t n, Location at);

  // Actions one group holds on the robot's controller.
  std::size_t capacity() const { return group_capacity(robot_.profile); }
  // Actions the walk may make: every group the dance may take.
  std::uint64_t budget() const { return std::uint64_t{capacity()} * groups_; }
  std::size_t groups_ = 1;
  std::optional<ExactMs> over_budget_time_;

  const Robot& robot_;
  const RobotStart& start_;
  std::vector<std::uint8_t> start_reads_;  // ServoWalk::start_reads
  std::vector<std::optional<int>> pos_;
  bool mirrored_ = false;
  // A lower bound of the actions so far: once it passes the budget, repeats stop expanding.
  std::uint64_t min_actions_ = 0;
  bool truncated_ = false;
  // The step that made the count pass the group's limit, and how the walk got there: the walk
  // stops there, and the file is not fitted.
  std::optional<Location> over_budget_at_;
  std::vector<Reporter::Note> over_budget_notes_;
  std::optional<Location> sequence_at_;
  std::vector<LineRecord> lines_;   // every `path: line` move, in the order walked
  std::vector<ArmMove> arm_moves_;  // every step that moved an arm's joint, in the order walked
  // speed_within_tolerance() over distance / time, by easing and tolerance / distance: a
  // repeat's passes, a section's performances and moves of one shape ask again.
  std::map<std::pair<std::string, double>, double> speeds_within_tolerance_;
};

}  // namespace seqc::compiler
