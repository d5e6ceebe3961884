// The Raspblock front end's state while it walks a file's steps (private to
// raspblock_lowering.cpp, which reads files, values and builds the packet stream, and
// raspblock_steps.cpp, which lowers each step). The board's outputs and their ranges are here.
//
// The walk (lists, repeat, include, sections, together, at, tempo, meter) is StepWalker's
// (step_walk.hpp), as for the servo controllers: beats and bars go through the timeline's tempo
// map, and a `together` block runs each track from the block's start. In a block pan, tilt,
// each of servo1-4 and the drive belong to one track each; packets from the tracks are put in
// time order when the walk ends, and the gimbal packets (one command carries pan and tilt)
// merged by instant, so pan in one track and tilt in another share each packet.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <tuple>
#include <vector>

#include "base/units.hpp"
#include "compiler/frontend/positions.hpp"
#include "compiler/frontend/scope_chain.hpp"
#include "compiler/frontend/step_parts.hpp"
#include "compiler/frontend/step_walk.hpp"
#include "compiler/targets/raspblock/raspblock_link.hpp"
#include "compiler/targets/raspblock/raspblock_lowering.hpp"
#include "compiler/targets/raspblock/raspblock_settings.hpp"
#include "compiler/timeline/easing.hpp"

namespace seqc::compiler {

// The board's positional outputs (docs/protocol/raspblock.md, function 02): the two gimbal
// servos travel together in one packet; servos 1-4 each have their own.
struct Channel {
  std::string_view name;
  int min;
  int max;
  bool gimbal;         // part of the two-servo gimbal packet
  std::uint8_t index;  // gimbal: 0 horizontal, 1 vertical; single: servo number 1-4
};
inline constexpr std::array<Channel, 6> kChannels = {{
    {"pan", 500, 2500, true, 0},
    {"tilt", 500, 1950, true, 1},
    {"servo1", 500, 2500, false, 1},
    {"servo2", 500, 2500, false, 2},
    {"servo3", 500, 2500, false, 3},
    {"servo4", 500, 2500, false, 4},
}};
inline constexpr std::size_t kPan = 0;
inline constexpr std::size_t kTilt = 1;
// Pulse widths in microseconds: 1500 is the neutral position; 0-180 degrees spans 500-2500.
inline constexpr int kHome = 1500;
inline constexpr double kDegreeZero = 500.0;
inline constexpr double kUnitsPerDegree = 2000.0 / 180.0;

inline std::string grouped(std::uint64_t n) { return format_grouped(static_cast<long long>(n)); }

using LocationKey = std::tuple<std::uint32_t, std::uint32_t, std::uint32_t>;
inline LocationKey key_of(const Location& at) { return {at.file, at.line, at.column}; }

extern const StepTable kRaspblockSteps;

class RaspblockLowering final : public StepWalker {
 public:
  RaspblockLowering(const Robot& robot, FileLoader& loader, Reporter& reporter)
      : StepWalker(loader, reporter, kRaspblockSteps, {kPan, kTilt}, kChannels.size()),
        robot_(robot) {}

  RaspblockProgram run(const LoadedFile& main);

 private:
  // ---- files ---------------------------------------------------------------------------------

  void run_file(const LoadedFile& f, bool is_main) override;
  FileScope& scope_for(const LoadedFile& f);

  // ---- values --------------------------------------------------------------------------------

  std::vector<std::string> channel_names() const;
  void parse_poses(const YamlNode& poses, FileScope& scope);
  std::vector<PositionEntry> parse_targets(const YamlNode& map, const std::string& where);
  static double absolute_units(const PositionEntry& t);
  bool check_limits(const PositionEntry& t, double units, std::string how,
                    std::optional<Reporter::Note> note = {});
  // A written time, exact (beats at any tempo stay fractions); nullopt after reporting.
  std::optional<ExactMs> exact_time(const YamlNode& node, std::string_view what);

  // ---- steps ---------------------------------------------------------------------------------

  // drive, move and wait.
  void own_step(const YamlNode& verb, const YamlNode& step) override;
  // A drive before the gap stops when its own step ends; nothing else is sent.
  bool hold_until(ExactMs target, const YamlNode& at) override;
  bool stopped() const override { return full_; }
  std::unique_ptr<RepeatBudget> repeat_budget(const YamlNode& step, long long times) override;
  std::unique_ptr<BlockRun> block_run(const YamlNode& step) override;
  friend class RaspblockRepeatBudget;
  friend class RaspblockBlockRun;
  void motion_step(const YamlNode& step, const YamlNode* drive_node, const YamlNode* move_node);

  // Resolves a move's targets into device units; false after reporting a mistake.
  bool resolve_move(const YamlNode& target, std::map<std::size_t, int>& out);

  // Splits a move into n packets per output: the k-th (1..n) carries the position at k/n of
  // the way and is sent at (k-1)/n of the time, so the servo reaches the target as the step
  // ends. An output without a known start goes straight to its target in the first packet.
  // A packet that would repeat the previous value of its output is left out.
  // Times are exact: each packet's send time is rounded once, on the absolute timeline, so
  // steps of fractional milliseconds (beats at 128 bpm are 468.75 ms) never drift.
  void interpolate(Location at, ExactMs start, ExactMs t, std::uint64_t n, Easing ease,
                   const std::map<std::size_t, int>& targets);
  void wait_step(const YamlNode& step, const YamlNode& value);
  // Marks the outputs a motion step moves (and the drive) as its track's; false after
  // reporting one that another track of a running block owns.
  bool claim(const std::map<std::size_t, int>& targets, bool drives, Location at);

  // ---- the stream ----------------------------------------------------------------------------

  // A drive lasts for its step: unless this step drives too (its speeds replace the old ones
  // at the same instant), the car is stopped before the step starts.
  void begin_step(bool drives);
  void advance(ExactMs t, Location at);
  void emit(raspblock::Packet packet, Location at) { emit_at(now_, std::move(packet), at); }
  // Sends at `at_time` rounded to the nearest millisecond of the stream's clock.
  void emit_at(ExactMs at_time, raspblock::Packet packet, Location at);
  void drop_superseded_speeds();
  // Before the stream is put in time order: each gimbal packet gets, of the axis its step did
  // not set, the value that axis has at its instant (tracks are walked one after another, not in
  // time order); gimbal packets of one millisecond become one, at the first's place. Reports an
  // axis that has no value yet where the other is sent.
  void merge_gimbal_packets();
  void check_capacity();
  const Robot& robot_;
  std::array<std::optional<int>, kChannels.size()> pos_;
  bool stop_due_ = false;
  bool full_ = false;
  Location last_drive_at_;
  Location end_at_;
  std::vector<TimedPacket> packets_;
  // Per gimbal packet (its index in packets_ before the time sort), the axes its step set.
  struct GimbalSet {
    std::optional<int> pan, tilt;
  };
  std::map<std::size_t, GimbalSet> gimbal_sets_;
  std::map<LocationKey, std::vector<Location>> include_sites_;
};

}  // namespace seqc::compiler
