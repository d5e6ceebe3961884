// Show files: several performers (an arm, a car, ...) on one clock.
//
//   show: duet
//   performers:
//     arm: {file: arm.yaml, port: /dev/ttyUSB0, group: 0}
//     car: {file: car.yaml, port: /dev/ttyAMA0}
//
// Each performer is a choreography file (relative to the show file) and the port it plays on;
// `group` (0-254, default 0) is the action group a servo controller stores it in. A show file
// is recognised by its top-level `show:` key. Loading checks the show file itself (keys, with
// "did you mean") and compiles every performer's file with its own diagnostics.
#pragma once

#include <string>
#include <vector>

#include "compiler/compile.hpp"

namespace seqc::compiler {

struct Performer {
  std::string name;
  std::string file;  // as resolved from the show file's folder
  std::string port;  // "" when the show file gives none
  int group = 0;
  Location at;  // the performer's entry in the show file
  CompileOutput output;
};

struct ShowOutput {
  SourceManager sources;  // the show file itself
  Diagnostics diagnostics;
  std::optional<std::string> read_error;
  std::string name;
  std::vector<Performer> performers;

  bool ok(bool strict = false) const;  // the show file and every performer compiled
  // Every file the show read: the show file, then each performer's CompileOutput::inputs().
  std::vector<std::string> inputs() const;
};

// Whether `text` is a show file (a top-level `show:` key), cheaply, before parsing it
// (load.hpp tells the two kinds of file apart with it).
bool is_show_text(const std::string& text);

ShowOutput load_show(const std::string& path, FileReader& files,
                     const CompileOptions& options = {});

}  // namespace seqc::compiler
