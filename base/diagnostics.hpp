// Compiler-style diagnostics: user mistakes are collected, not thrown,
// and rendered like clang:
//
//   walk.yaml:12:7: error: unknown key 'tme'; did you mean 'time'?
//         tme: 500ms
//         ^
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "base/source.hpp"

namespace seqc {

enum class Severity { Error, Warning, Note };

struct Diagnostic {
  Severity severity = Severity::Error;
  Location location;
  std::string message;
};

class Diagnostics {
 public:
  void error(Location at, std::string message);
  void warning(Location at, std::string message);
  // A note attaches to the diagnostic before it ("note: included from here").
  void note(Location at, std::string message);

  // With strict, warnings count as errors (--strict).
  bool has_errors(bool strict = false) const;
  std::size_t error_count() const { return errors_; }
  std::size_t warning_count() const { return warnings_; }
  const std::vector<Diagnostic>& all() const { return list_; }

 private:
  std::vector<Diagnostic> list_;
  std::size_t errors_ = 0;
  std::size_t warnings_ = 0;
};

// "path:line:col: error: message", the source line, and a caret under the column. A line that
// is not plain text (control bytes, invalid UTF-8: a binary file) is not quoted, nor is a line of
// a file whose lines the SourceManager withholds (an include that is no choreography), so a
// file's bytes never reach a terminal; the path and the message show any control character as
// an escape (base/terminal_text.hpp), so a value quoted from a file cannot forge a line.
// With strict, warnings are rendered as errors. With color, ANSI SGR codes as clang uses them:
// bold location and message, red error, magenta warning, cyan note, green caret.
std::string render(const Diagnostic& d, const SourceManager& sources, bool strict = false,
                   bool color = false);
std::string render_all(const Diagnostics& ds, const SourceManager& sources, bool strict = false,
                       bool color = false);

// The closest candidate to `word` by edit distance, or "" if none is close enough.
std::string did_you_mean(std::string_view word, const std::vector<std::string>& candidates);

}  // namespace seqc
