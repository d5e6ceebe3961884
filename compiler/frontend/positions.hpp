// Positions as the choreography writes them (`pan: 1500`, `claw: +10deg`, `tilt: home`), shared
// by every robot kind: parsing one entry, and the messages for limits and relative moves. What
// an output is called and how degrees map to units stay with each robot kind.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

#include "base/units.hpp"
#include "compiler/frontend/reporter.hpp"
#include "compiler/frontend/yaml/yaml_tree.hpp"
#include "compiler/timeline/timeline.hpp"

namespace seqc::compiler {

struct PositionEntry {
  std::size_t output = 0;  // index of the servo or output it names
  std::string written;     // as in the file, for messages
  bool home = false;       // the keyword `home`
  PositionValue value;
  Location at;
  // The group the entry names the output through (`left: +100` for each of left's servos), and
  // where that group lists it; empty when the output is named itself. Messages about the entry
  // name the output, with a note at `listed_at`.
  std::string group;
  Location listed_at;
};

// The note that says an entry came through a group (nullopt for an output named itself);
// `name` is the output's name.
std::optional<Reporter::Note> group_note(const PositionEntry& e, std::string_view name);

// The entry `key: value` for the already identified `output`; nullopt after reporting.
// `examples` lists sample values for the message, e.g. "500, 90deg, +50".
std::optional<PositionEntry> parse_position_entry(const YamlNode& key, const YamlNode& value,
                                                  std::size_t output, std::string_view examples,
                                                  Reporter& reporter);

// Reports a curve (a move's segment) that passes outside [min, max] on the output called
// `name` at its true extreme (value_range), though both its ends are within: an overshooting
// ease. Every robot kind checks every curve it will send with this. True when within.
bool check_curve_limits(const Segment& segment, std::string_view name, long long min, long long max,
                        Location at, const std::optional<Reporter::Note>& note, Reporter& reporter);

// Reports `units` outside [min, max] on the output called `name`; `how` explains where the value
// came from (empty: the written value when it was in degrees). True when within the limits.
bool check_position_limits(const PositionEntry& e, std::string_view name, long long min,
                           long long max, double units, std::string how,
                           std::optional<Reporter::Note> note, Reporter& reporter);

// A relative entry's position: `base` plus `delta` units, with `how` set to e.g. "1500 +100".
// Without a known base this reports, naming the output `name`, and returns nullopt.
std::optional<double> relative_units(const PositionEntry& e, std::string_view name,
                                     const std::optional<int>& base, double delta, std::string& how,
                                     const std::optional<Reporter::Note>& note, Reporter& reporter);

}  // namespace seqc::compiler
