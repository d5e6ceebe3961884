#include "base/diagnostics.hpp"

#include <algorithm>
#include <string>
#include <utility>

#include "base/terminal_text.hpp"

namespace seqc {

void Diagnostics::error(Location at, std::string message) {
  list_.push_back({Severity::Error, at, std::move(message)});
  ++errors_;
}

void Diagnostics::warning(Location at, std::string message) {
  list_.push_back({Severity::Warning, at, std::move(message)});
  ++warnings_;
}

void Diagnostics::note(Location at, std::string message) {
  list_.push_back({Severity::Note, at, std::move(message)});
}

bool Diagnostics::has_errors(bool strict) const { return errors_ > 0 || (strict && warnings_ > 0); }

namespace {

// The caret line copies tabs from the source line and gives every other character one column,
// so the caret sits under the right character in a terminal. UTF-8 continuation bytes and the
// zero-width byte-order mark take no column.
std::string caret_padding(std::string_view line, std::size_t column) {
  std::string pad;
  const std::size_t n = std::min(column - 1, line.size());
  for (std::size_t i = 0; i < n; ++i) {
    const auto c = static_cast<unsigned char>(line[i]);
    if (c == '\t') {
      pad += '\t';
    } else if (c == 0xEF && i + 2 < line.size() &&
               static_cast<unsigned char>(line[i + 1]) == 0xBB &&
               static_cast<unsigned char>(line[i + 2]) == 0xBF) {
      i += 2;  // U+FEFF
    } else if ((c & 0xC0) != 0x80) {
      pad += ' ';
    }
  }
  return pad;
}

// Whether a source line may be copied to a terminal: tabs, printable ASCII and well-formed
// UTF-8 only. A line with a control byte (NUL, an escape sequence) or a stray byte of a binary
// file is not quoted, so the file's bytes never reach the terminal.
bool quotable(std::string_view line) {
  for (std::size_t i = 0; i < line.size(); ++i) {
    const auto c = static_cast<unsigned char>(line[i]);
    if (c == '\t' || (c >= 0x20 && c < 0x7F)) continue;
    if (c == '\r' && i + 1 == line.size()) continue;  // a CRLF line end
    std::size_t len = 0;
    if (c >= 0xC2 && c <= 0xDF) {
      len = 2;
    } else if (c >= 0xE0 && c <= 0xEF) {
      len = 3;
    } else if (c >= 0xF0 && c <= 0xF4) {
      len = 4;
    } else {
      return false;
    }
    if (i + len > line.size()) return false;
    for (std::size_t k = 1; k < len; ++k) {
      if ((static_cast<unsigned char>(line[i + k]) & 0xC0) != 0x80) return false;
    }
    // C1 control characters (U+0080..U+009F) act like escapes on some terminals.
    if (c == 0xC2 && static_cast<unsigned char>(line[i + 1]) < 0xA0) return false;
    i += len - 1;
  }
  return true;
}

}  // namespace

// Layout (stable; golden-tested in tests/compiler/diagnostics_test.cpp):
//   path:line:col: error: message
//      12 |   source line
//         |   ^
// Without a column the caret line is left out; with line 0 only "path: error: message" is
// printed; a line that is not plain text (a control byte, invalid UTF-8) is not quoted, nor is
// any line of a file whose lines the SourceManager withholds; the path and the message show
// their control characters as escapes (terminal_safe); a location
// in no known file (kNoFile or a stale index) prints "seqc: error: message".
std::string render(const Diagnostic& d, const SourceManager& sources, bool strict, bool color) {
  const Location& at = d.location;
  const bool known_file = at.file < sources.file_count();
  const auto sgr = [color](const char* code) { return color ? std::string(code) : std::string(); };
  std::string out = sgr("\033[1m");
  if (!known_file) {
    out += "seqc";
  } else {
    out += terminal_safe(sources.path(at.file));
    if (at.line > 0) {
      out += ':' + std::to_string(at.line);
      if (at.column > 0) out += ':' + std::to_string(at.column);
    }
  }
  const bool promoted = strict && d.severity == Severity::Warning;
  switch (d.severity) {
    case Severity::Error:
      out += ": " + sgr("\033[31m") + "error: ";
      break;
    case Severity::Warning:
      out += promoted ? ": " + sgr("\033[31m") + "error: " : ": " + sgr("\033[35m") + "warning: ";
      break;
    case Severity::Note:
      out += ": " + sgr("\033[36m") + "note: ";
      break;
  }
  out += sgr("\033[0m\033[1m") + terminal_safe(d.message);
  if (promoted) out += " [--strict]";
  out += sgr("\033[0m") + '\n';

  // No source line to quote: an unknown file, no line, a file refused unread (empty text) or one
  // whose lines are withheld (an include that is no choreography: it could be any file).
  if (!known_file || at.line == 0 || sources.text(at.file).empty()) return out;
  if (!sources.quotes_lines(at.file)) return out;
  if (at.line > sources.line_count(at.file)) return out;

  const std::string number = std::to_string(at.line);
  const std::size_t width = std::max<std::size_t>(5, number.size() + 1);
  const std::string_view line = sources.line(at.file, at.line);
  if (!quotable(line)) return out;
  out += std::string(width - number.size(), ' ') + number + " | ";
  out += line;
  out += '\n';
  if (at.column > 0) {
    out += std::string(width, ' ') + " | " + caret_padding(line, at.column) + sgr("\033[32m") +
           "^" + sgr("\033[0m") + "\n";
  }
  return out;
}

std::string render_all(const Diagnostics& ds, const SourceManager& sources, bool strict,
                       bool color) {
  std::string out;
  for (const Diagnostic& d : ds.all()) out += render(d, sources, strict, color);
  return out;
}

}  // namespace seqc
