// The step walk every robot kind shares, so the servo-controller and Raspblock front ends read
// time and structure alike. StepWalker walks a file's steps with one step table: lists,
// `repeat`, `include`, `section` (with `params`, `with` and `$name`), `together`, `at:`,
// `tempo` and `meter`, with beats and bars counted through the timeline's tempo map; a front
// end derives from it and supplies only what is its own: its file keys, outputs, positions and
// limits, its motion steps (and `wait`), and how it holds, repeats and runs tracks within its
// budget.
//
// The free functions are the walk's pieces: each reports what is wrong with what it reads and
// returns nullopt / nullptr / false.
//
// The walk has budgets of its own, counted as it goes (a fan-out of sections or includes would
// otherwise run for ever before anything counted it): sections performing sections, blocks
// (`together`, `repeat`, a front end's `mirror`) inside blocks, steps walked and includes
// expanded in all. Passing one is a located error naming how the walk got there, and the walk
// stops. Every nested step list is the main sequence, an included file's (kMaxIncludeDepth),
// a section's or a block's, so no input makes the walk recurse deeper than
// 1 + kMaxIncludeDepth + kMaxSectionDepth + kMaxBlockDepth lists.
#pragma once

#include <cstddef>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "compiler/frontend/file_loader.hpp"
#include "compiler/frontend/reporter.hpp"
#include "compiler/frontend/scope_chain.hpp"
#include "compiler/frontend/sections.hpp"
#include "compiler/frontend/step_times.hpp"
#include "compiler/frontend/walk_performances.hpp"
#include "compiler/frontend/yaml/yaml_tree.hpp"
#include "compiler/timeline/exact_time.hpp"
#include "compiler/timeline/tempo_map.hpp"
#include "compiler/timeline/timeline.hpp"

namespace seqc::compiler {

// Sections performing sections, and blocks (`together`, `repeat`, `mirror`) inside blocks,
// through any number of sections and includes: deeper is taken for a runaway chain.
inline constexpr std::size_t kMaxSectionDepth = 64;
inline constexpr std::size_t kMaxBlockDepth = 64;
// Steps walked in all (each performance of a section, pass of a repeat and include counts its
// steps again): far beyond what a group's actions need, yet fast to walk and hold.
inline constexpr std::size_t kMaxWalkedSteps = 200'000;
// Files included in all (each include step walked counts once).
inline constexpr std::size_t kMaxIncludesWalked = 10'000;

// `node` (a time) after `from`: ms and s as written, beats and bars counted through `map`;
// nullopt after reporting.
std::optional<ExactMs> musical_time(const TempoMap& map, const YamlNode& node,
                                    std::string_view what, ExactMs from, Reporter& reporter);

// The instant of `at: bar N` / `at: bar N beat B` on `map`; nullopt after reporting.
std::optional<ExactMs> bar_position(const TempoMap& map, const YamlNode& at, Reporter& reporter);

// Where a step's `at` (`at_node`) puts it, for a list that started at `list_start` and has run
// until `now`: an offset from the list's start, or a bar position. nullopt after reporting one
// that is not a time or lies in the past.
std::optional<ExactMs> at_target(const TempoMap& map, const YamlNode& at_node, ExactMs now,
                                 ExactMs list_start, Reporter& reporter);

// Sets the meter from `now` on after checking that `now` is on a bar line (`what` names the
// change for the message); false after reporting. Each note keeps its length (tempo_map.hpp).
bool change_meter(TempoMap& map, ExactMs now, TimeSignature meter, Location at,
                  std::string_view what, Reporter& reporter);

// The running `together` blocks (outermost first) and which of their tracks owns each output.
// An output is a number the front end chooses (a servo, or a unit such as the car's gimbal);
// it may move in one track of each running block only, however deep inside it.
class TrackClaims {
 public:
  struct Track {
    std::string name;
    Location at;
    std::vector<std::size_t> outputs;  // moved so far (in it or in blocks inside it), in order
  };

  void begin_block() { blocks_.emplace_back(); }
  // The track of the innermost block that runs from now on; it lives until the next
  // begin_track or end_block.
  void begin_track(std::string name, Location at);
  void end_block();

  // The innermost running track; nullptr outside every `together`.
  const Track* track() const { return blocks_.empty() ? nullptr : &blocks_.back().track; }
  bool in_block() const { return !blocks_.empty(); }

  // Marks `output` as moved by the running tracks; false after reporting it in two tracks of
  // one block: `who` + " " + `verb` + " in two tracks, 'a' and 'b'; " + `rule`.
  bool claim(std::size_t output, std::string_view who, std::string_view verb, std::string_view rule,
             Location at, Reporter& reporter);

  // Reports a tempo or meter step (`verb`) inside a track (it would change the other tracks'
  // beats too); false if it is one.
  bool outside_tracks(const YamlNode& value, std::string_view verb, Reporter& reporter) const;

 private:
  struct Block {
    Track track;
    std::map<std::size_t, std::pair<std::string, Location>> claimed;
  };
  std::vector<Block> blocks_;
};

// What a front end's steps look like, beyond the verbs every kind shares (repeat, include,
// section, together, tempo, meter).
struct StepTable {
  std::vector<std::string_view> verbs;       // the front end's own verbs
  std::vector<std::string_view> combinable;  // own verbs that may share one step
  std::vector<std::string_view> step_keys;   // every key of a step, for "did you mean"
  std::string_view needs_one_of;             // the message for a step without a verb
  std::string_view example;                  // "'move: home' or 'wait: 1s'"
  std::string_view include_example;          // a file name, for a missing include path
  std::string_view together_example;         // "'together: {arm: [...], claw: [...]}'"
  ScopeChain::CannotLoad cannot_include = nullptr;
};

class StepWalker {
 public:
  virtual ~StepWalker() = default;
  // What was performing when (walk_performances.hpp).
  using Performances = WalkPerformances;

  StepWalker(const StepWalker&) = delete;
  StepWalker& operator=(const StepWalker&) = delete;

  // Records when each step runs into `times` (which outlives the walk); null: nothing.
  void record_times(StepTimes* times) { times_ = times; }

  // A repeat's passes, within the front end's budget: before_pass(i) before each pass (false
  // stops the repeat; the budget has counted the passes left), after_pass(i) after each pass
  // without new errors (false stops it).
  class RepeatBudget {
   public:
    virtual ~RepeatBudget() = default;
    virtual bool before_pass(long long pass) = 0;
    virtual bool after_pass(long long pass) = 0;
  };
  // A `together` block's tracks, within the front end's budget and rules: track_begins before
  // each track runs from the block's start, track_ends after it, block_ends with the block's
  // start and the end of its longest track (the clock is then at that end).
  class BlockRun {
   public:
    virtual ~BlockRun() = default;
    virtual void track_begins() {}
    virtual void track_ends() {}
    virtual void block_ends(ExactMs /*start*/, ExactMs /*longest*/) {}
  };

 protected:
  // `home_outputs`: what the built-in pose `home` moves; `outputs`: the timeline's outputs.
  StepWalker(FileLoader& loader, Reporter& reporter, const StepTable& table,
             std::vector<std::size_t> home_outputs, std::size_t outputs);

  // ---- what a front end supplies ------------------------------------------------------------

  // A file: its keys, its scope, then run_sequence; `is_main` for the main file.
  virtual void run_file(const LoadedFile& f, bool is_main) = 0;
  // One of the table's own verbs (`verb`, the key naming it) in `step`.
  virtual void own_step(const YamlNode& verb, const YamlNode& step) = 0;
  // Whether `key` names a verb in `step` (a front end may take a verb's name as a setting).
  virtual bool is_verb(std::string_view key, const YamlNode& step) const;
  // Holds from now until `target` (a step's `at:`, written at `at`), moving the clock there;
  // false after reporting.
  virtual bool hold_until(ExactMs target, const YamlNode& at) = 0;
  // True once the walk cannot go on (the front end's budget is spent, already reported).
  virtual bool stopped() const { return false; }
  // True once the walk's own budget or the front end's is spent (see stopped()).
  bool halted() const { return halted_ || stopped(); }

  // The budget of the repeat `step` of `times` passes, and the run of the `together` `step`
  // (made as the block starts).
  virtual std::unique_ptr<RepeatBudget> repeat_budget(const YamlNode& step, long long times) = 0;
  virtual std::unique_ptr<BlockRun> block_run(const YamlNode& step) = 0;

  // ---- the walk -----------------------------------------------------------------------------

  // The main file's or an included file's `sequence` (of `root`, the file's map), with the
  // file's scope running and its tempo and meter in force.
  void run_sequence(const YamlNode& root, FileScope& scope, const YamlNode& sequence, bool is_main);
  void run_steps(const YamlNode& list, std::string_view what);
  void run_step(const YamlNode& step);
  // Moves the clock to the step's `at:`; false after reporting.
  bool apply_at(const YamlNode& step);
  // `node` (a time) after `from`, through the tempo map; nullopt after reporting.
  std::optional<ExactMs> musical_time(const YamlNode& node, std::string_view what, ExactMs from);
  bool change_meter(TimeSignature meter, Location at, std::string_view what);
  // Counts a block (`verb`, written at `at`) whose steps run inside the running ones; false
  // after reporting one nested more than kMaxBlockDepth deep (the walk then stops). Each true
  // is followed by close_block() once the block's steps have run.
  bool open_block(Location at, std::string_view verb);
  void close_block() { --blocks_deep_; }
  // The walk stops here: `message` at `at`, with notes naming every performance and include
  // that led here.
  void halt(Location at, std::string message);

  Performances performances_;

  struct ListFrame {
    ExactMs start;                    // for `at:`
    std::optional<double> tolerance;  // a `tolerance:` step in this list (servo controllers)
  };

  FileLoader& loader_;
  Reporter& reporter_;
  ScopeChain scopes_;
  Timeline timeline_;
  ExactMs now_;
  std::vector<ListFrame> lists_;
  TrackClaims claims_;  // the running `together` blocks

 private:
  void repeat_step(const YamlNode& step, const YamlNode& value);
  void include_step(const YamlNode& value);
  void section_step(const YamlNode& step, const YamlNode& value);
  // After a walk of the main file that reached its end without an error: a warning at each of
  // its sections that no performance reached (an error can keep a performance from being
  // walked, and a halted walk never read its end).
  void warn_unperformed_sections(const FileScope& main);
  void together_step(const YamlNode& step, const YamlNode& tracks);
  void walk_step(const YamlNode& step);
  void tempo_step(const YamlNode& value);
  // With a song (`music:`), a tempo or meter anywhere else is an error: true after reporting.
  bool song_owns(const YamlNode& value, std::string_view key);
  // An included file may not bring a song (its own tempo and meter are for checking it alone
  // and give way to the song's map while one plays).
  void check_included_music(const YamlNode& root);
  void meter_step(const YamlNode& value);

  const StepTable& table_;
  std::vector<const YamlNode*> sections_running_;  // for cycle detection
  std::set<const YamlNode*> sections_performed_;   // every section a performance reached
  std::vector<std::string_view> section_names_;    // the running sections, outermost first
  std::size_t blocks_deep_ = 0;
  std::size_t steps_walked_ = 0;
  std::size_t includes_walked_ = 0;
  bool halted_ = false;
  StepTimes* times_ = nullptr;
  std::vector<std::uint64_t> timed_steps_;  // the steps being walked, innermost last
};

}  // namespace seqc::compiler
