// `seqc import`: a .d6a table as a readable choreography whose compiled actions are the rows:
// one step per row, its Time, and the servos that changed since the row before (the first row
// names every servo; a row that changes nothing is a wait, which re-sends every position).
// The robot is `xarm` for 6 servo columns and `bus` otherwise, unless one is given; with `bus`
// the file names the servos s1..sN it has, so `seqc export` writes N columns again.
#pragma once

#include <string>

#include "base/result.hpp"
#include "compiler/formats/d6a.hpp"

namespace seqc::compiler {

struct ImportOptions {
  std::string name;     // the choreography's name (the file's stem)
  std::string source;   // shown in the header comment
  std::string profile;  // "" chooses by the number of servo columns
};

// The options for importing the file at `path` with `profile`: its file name shown as the
// source and its stem as the name; for "-" (standard input) `stdin_name` and "imported".
ImportOptions import_options_for(const std::string& path, const std::string& stdin_name,
                                 const std::string& profile);

// The YAML text, or an error naming the row and column that cannot become an action (a time
// outside 20-30,000 ms, a position outside the profile's range, an id the profile lacks).
Result<std::string> choreography_from_d6a(const compiler::D6aTable& table,
                                          const ImportOptions& options);

}  // namespace seqc::compiler
