// `seqc check --format json|sarif`: the diagnostics of every file checked, for programs.
//
// json: an array with one object per diagnostic (docs/cli.md):
//   {"file": "walk.yaml", "line": 12, "column": 7, "severity": "error",
//    "rule": "unknown-key", "message": "...",
//    "notes": [{"file": ..., "line": ..., "column": ..., "message": "included from here"}]}
// line and column are 1-based as in the text form; both are left out only when the problem
// is the file as a whole (it cannot be read). With --strict warnings have severity "error".
//
// sarif: a SARIF 2.1.0 log with one run; each diagnostic is a result with its rule id, level,
// message and physical location, and its notes as related locations.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "base/diagnostics.hpp"
#include "base/source.hpp"

namespace seqc {

// One file checked: its diagnostics with the sources they point into, or why it could not be
// read. The pointers outlive the call.
struct CheckedFile {
  std::string path;  // as given (or <stdin>)
  const SourceManager* sources = nullptr;
  const Diagnostics* diagnostics = nullptr;
  std::optional<std::string> read_error;
};

std::string diagnostics_json(const std::vector<CheckedFile>& files, bool strict);
std::string diagnostics_sarif(const std::vector<CheckedFile>& files, bool strict,
                              const std::string& version);

}  // namespace seqc
