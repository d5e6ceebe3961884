// The `robot:` section: a built-in profile, optionally refined by per-file servo definitions
// and a left/right mirror table (docs/language.md, "The robot").
#pragma once

#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "compiler/frontend/profiles.hpp"
#include "compiler/frontend/reporter.hpp"
#include "compiler/frontend/yaml/yaml_tree.hpp"
#include "compiler/program/program.hpp"

namespace seqc::compiler {

struct Robot {
  const RobotProfile* profile = nullptr;
  RobotInfo info;
  std::map<std::string, std::size_t, std::less<>> names;  // every name (and alias) -> servo index
  std::map<std::size_t, std::size_t> mirror;              // servo index -> its mirror image
  bool has_mirror_table = false;
  // The servos the built-in pose `home` moves: the named ones (all channels if none is named).
  std::vector<std::size_t> home_servos;
  // How the board moves a servo during an action: the profile's, or the file's `controller:`.
  ControllerModel controller = ControllerModel::StraightLine;

  std::vector<std::string> name_list() const;
  // Device units for a position written in degrees (absolute) or a degree offset (relative).
  double degrees_to_units(double degrees, bool relative) const;
};

// Parses the main file's `robot:` value (a profile name or a map). nullopt if the profile
// cannot be determined; other mistakes are reported and the section applied as far as possible.
std::optional<Robot> parse_robot(const YamlNode& value, Reporter& reporter);

// The robot a choreography's text names, for tools that edit the file without compiling it
// (`seqc teach`): its servos with their names. Errors go to `diags` with their locations.
std::optional<RobotInfo> robot_of_text(const std::string& path, const std::string& text,
                                       SourceManager& sources, Diagnostics& diags);

// A main file without `robot:`: "missing 'robot'", or, for a show file (it has `performers:`),
// that it is a show and `seqc show PATH` runs it.
void report_missing_robot(const YamlNode& root, const std::string& path, Reporter& reporter);

// The profile name an included file's `robot:` names (it may not define servos).
std::optional<std::string> included_robot_name(const YamlNode& value, Reporter& reporter);

// Parses a whole number of `value` within [lo, hi]; reports and returns nullopt otherwise.
std::optional<long long> parse_integer(const YamlNode& value, long long lo, long long hi,
                                       std::string_view what, Reporter& reporter);

}  // namespace seqc::compiler
