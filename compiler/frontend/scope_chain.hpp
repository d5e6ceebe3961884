// The files whose steps are running (the main file and the includes that led to the current
// step), and what each contributes while they run: its poses, tempo and resolution. Shared by
// every robot kind: times with beats, pose lookup with "did you mean", and include loading with
// its cycle and depth checks.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "base/units.hpp"
#include "compiler/frontend/file_loader.hpp"
#include "compiler/frontend/positions.hpp"
#include "compiler/frontend/reporter.hpp"
#include "compiler/frontend/yaml/yaml_tree.hpp"
#include "compiler/timeline/exact_time.hpp"
#include "compiler/timeline/song.hpp"
#include "compiler/timeline/tempo_map.hpp"

namespace seqc::compiler {

struct Pose {
  std::vector<PositionEntry> entries;
  Location at;
};

// Outputs a move names together by one name (`groups: {left: [lf_coxa, lm_coxa]}`): each member
// gets the value written for the group, as if it were written out for each.
struct OutputGroup {
  std::vector<std::size_t> members;
  std::vector<Location> member_at;  // where the group lists each member
  Location at;                      // the group's name
};

// What a file contributes while its steps run.
struct FileScope {
  const LoadedFile* file = nullptr;
  std::map<std::string, Pose, std::less<>> poses;
  std::map<std::string, OutputGroup, std::less<>> groups;
  std::optional<Tempo> tempo;
  std::optional<TimeSignature> meter;
  std::optional<Song> song;           // `music:`: its tempo and meter at bar 1 are the above
  std::optional<SongFile> song_file;  // `music:`'s audio file, also when the block has mistakes
  std::optional<std::uint32_t> resolution_ms;
  std::optional<double> tolerance;                               // device units
  std::map<std::string, const YamlNode*, std::less<>> sections;  // name -> its step list
  std::map<std::string, Location, std::less<>> section_at;       // name -> where it is named
};

class ScopeChain {
 public:
  // `home_outputs`: the outputs the built-in pose `home` moves to their home positions.
  explicit ScopeChain(std::vector<std::size_t> home_outputs)
      : home_outputs_(std::move(home_outputs)) {}

  // The scope of `f` (whose root is a map) and whether it was just made: a new scope has its
  // 'tempo' (or its `music:` song) parsed; its poses and resolution are for the caller to fill in.
  std::pair<FileScope&, bool> open(const LoadedFile& f, Reporter& reporter);

  void push(FileScope& scope) { chain_.push_back(&scope); }
  void pop() { chain_.pop_back(); }

  // The innermost resolution, tempo, meter and tolerance set by a running file, if any.
  std::optional<std::uint32_t> resolution_ms() const;
  std::optional<Tempo> tempo() const;
  std::optional<TimeSignature> meter() const;
  std::optional<double> tolerance() const;

  // The section `name` from the innermost running file that defines it; nullptr after
  // reporting an unknown name with "did you mean".
  const YamlNode* find_section(const YamlNode& name, Reporter& reporter) const;

  // `node` as exact milliseconds: 500ms, 1.5s, 1/3s, beats at the innermost file's tempo (a
  // beat being the innermost meter's note value), bars at the innermost meter. nullopt after
  // reporting.
  std::optional<ExactMs> exact_ms(const YamlNode& node, std::string_view what,
                                  Reporter& reporter) const;

  // `node` in milliseconds (500ms, 1.5s, or beats at the innermost tempo). Above `max_ms` the
  // message is "'<value>' " + `too_long`. nullopt after reporting.
  std::optional<std::uint32_t> time_ms(const YamlNode& node, std::string_view what,
                                       std::uint64_t max_ms, std::string_view too_long,
                                       Reporter& reporter) const;

  // The pose `name` from the innermost file that defines it, else the built-in `home`; reports
  // an unknown name with "did you mean" and returns nullptr.
  const Pose* find_pose(const YamlNode& name, Reporter& reporter);

  // The group `name` from the innermost running file that defines it; nullptr if none does.
  const OutputGroup* find_group(std::string_view name) const;
  // Every group name of the running files, for "did you mean".
  std::vector<std::string> group_names() const;

  // Parses a map of `output: position` entries (`where` says where, for messages), reporting
  // what is wrong with them.
  using ParseEntries =
      std::function<std::vector<PositionEntry>(const YamlNode& map, const std::string& where)>;

  // The entries a move's target names: a pose (setting `note` to point at the move, unless it is
  // the built-in home), or an inline map parsed by `parse` into `inline_entries`. `noun` names an
  // output in the message for anything else ("servo"). nullptr after reporting.
  const std::vector<PositionEntry>* move_entries(const YamlNode& target, std::string_view noun,
                                                 const ParseEntries& parse,
                                                 std::vector<PositionEntry>& inline_entries,
                                                 std::optional<Reporter::Note>& note,
                                                 Reporter& reporter);

  // The file an include step names, loaded; nullptr after reporting a missing path, a cycle, a
  // chain deeper than kMaxIncludeDepth, or a file that cannot be loaded (`cannot_load` words
  // that message from the path and the loader's reason). `example` is a file name for the
  // message about a missing path.
  using CannotLoad = std::string (*)(const std::string& path, const std::string& reason);
  const LoadedFile* load_include(const YamlNode& value, std::string_view example,
                                 CannotLoad cannot_load, FileLoader& loader, Reporter& reporter);

 private:
  std::vector<std::size_t> home_outputs_;
  std::map<std::string, std::unique_ptr<FileScope>> scopes_;
  std::vector<FileScope*> chain_;  // files whose steps are running, outermost first
  std::unique_ptr<Pose> home_;
};

// A file's 'poses' into `scope`: `not_a_map` is the message for a 'poses' that is no map, and a
// pose that is no map "must be a map of " + `pose_shape`. `parse` reads each pose's entries.
void parse_poses(const YamlNode& poses, FileScope& scope, std::string_view not_a_map,
                 std::string_view pose_shape, const ScopeChain::ParseEntries& parse,
                 Reporter& reporter);

// The root of a choreography file when it is a map; nullptr after reporting otherwise (or when
// the file could not be parsed, already reported).
const YamlNode* file_root(const LoadedFile& f, Reporter& reporter);

// In an included file, false after reporting a 'robot' other than `profile`.
bool check_included_robot(const YamlNode& root, const std::string& profile, Reporter& reporter);

// The file's 'sequence'; nullptr after reporting that it is missing.
const YamlNode* find_sequence(const YamlNode& root, Reporter& reporter);

// `node` as a time value (500ms, 1.5s, 2b, 2bar); nullopt after reporting what is wrong with it
// (`what` names it in the message for a value that is no time at all).
std::optional<TimeValue> parse_time_node(const YamlNode& node, std::string_view what,
                                         Reporter& reporter);

// The errors for a time in beats where no tempo is set and one in bars where no meter is.
void report_no_tempo(const YamlNode& node, Reporter& reporter);
void report_no_meter(const YamlNode& node, Reporter& reporter);

// Parses a 'tempo': beats of the meter a minute, 1-1000, optionally written with "bpm"
// ('tempo: 120'), or notes of a named value a minute: a fraction of a whole note ('3/8 = 60')
// or a note name, optionally dotted ('dotted quarter = 60', 'eighth = 180').
std::optional<Tempo> parse_tempo(const YamlNode& node, Reporter& reporter);

// Parses 'meter: 6/8': beats per bar (1-32) over the beat's note value (1, 2, 4, 8, 16 or 32).
std::optional<TimeSignature> parse_meter(const YamlNode& node, Reporter& reporter);

}  // namespace seqc::compiler
