#include "compiler/frontend/yaml/yaml_prescan.hpp"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

namespace seqc::compiler::yaml_detail {

namespace {

std::string hex_byte(unsigned char c) {
  char buf[8];
  std::snprintf(buf, sizeof buf, "0x%02X", c);
  return buf;
}

std::string code_point(unsigned c) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "U+%04X", c);
  return buf;
}

// Length of the valid UTF-8 sequence at text[i] (a lead byte >= 0x80), or 0 if invalid.
std::size_t utf8_length(std::string_view text, std::size_t i) {
  const auto b0 = static_cast<unsigned char>(text[i]);
  std::size_t len = 0;
  unsigned lo = 0x80;
  unsigned hi = 0xBF;  // allowed range of the second byte
  if (b0 >= 0xC2 && b0 <= 0xDF) {
    len = 2;
  } else if (b0 >= 0xE0 && b0 <= 0xEF) {
    len = 3;
    if (b0 == 0xE0) lo = 0xA0;  // overlong
    if (b0 == 0xED) hi = 0x9F;  // surrogates
  } else if (b0 >= 0xF0 && b0 <= 0xF4) {
    len = 4;
    if (b0 == 0xF0) lo = 0x90;  // overlong
    if (b0 == 0xF4) hi = 0x8F;  // past U+10FFFF
  } else {
    return 0;
  }
  if (i + len > text.size()) return 0;
  for (std::size_t k = 1; k < len; ++k) {
    const auto b = static_cast<unsigned char>(text[i + k]);
    if (k == 1 ? (b < lo || b > hi) : (b < 0x80 || b > 0xBF)) return 0;
  }
  return len;
}

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }

}  // namespace

std::optional<ScanProblem> check_bytes(std::string_view text) {
  // A NUL anywhere means a binary (or UTF-16) file, whatever odd bytes come before it (a PNG
  // starts with 0x89): say so once, for the first NUL. YAML text never holds one.
  const auto not_text = [](std::size_t offset) {
    return "not a text file (byte 0x00 at offset " + std::to_string(offset) + ")";
  };
  if (const std::size_t nul = text.find('\0'); nul != std::string_view::npos) {
    const std::string_view before = text.substr(0, nul);
    const std::size_t line_start =
        before.rfind('\n') == std::string_view::npos ? 0 : before.rfind('\n') + 1;
    const auto lines = static_cast<std::uint32_t>(std::count(before.begin(), before.end(), '\n'));
    return ScanProblem{lines + 1, static_cast<std::uint32_t>(nul - line_start + 1), not_text(nul)};
  }
  std::uint32_t line = 1;
  std::size_t line_start = 0;
  auto at = [&](std::size_t i, std::string message) {
    return ScanProblem{line, static_cast<std::uint32_t>(i - line_start + 1), std::move(message)};
  };
  for (std::size_t i = 0; i < text.size(); ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c >= 0x20 && c < 0x7F) continue;  // printable ASCII: nearly every byte
    if (c == '\n') {
      ++line;
      line_start = i + 1;
    } else if (c == '\r') {
      if (i + 1 >= text.size() || text[i + 1] != '\n') {
        return at(i, "carriage return without a line feed (only LF and CRLF line ends are read)");
      }
    } else if ((c < 0x20 && c != '\t') || c == 0x7F) {
      return at(i, "control character " + code_point(c) + " is not allowed in YAML");
    } else if (c >= 0x80) {
      const std::size_t len = utf8_length(text, i);
      if (len == 0) return at(i, "invalid UTF-8 (byte " + hex_byte(c) + ")");
      i += len - 1;
    }
  }
  return std::nullopt;
}

bool quoted_scalar_closes(std::string_view text, std::size_t pos) {
  const char quote = text[pos];
  for (std::size_t i = pos + 1; i < text.size(); ++i) {
    if (quote == '"' && text[i] == '\\') {
      ++i;  // the escaped character cannot close the scalar
    } else if (text[i] == quote) {
      if (quote == '\'' && i + 1 < text.size() && text[i + 1] == '\'') {
        ++i;  // '' is an escaped quote
      } else {
        return true;
      }
    }
  }
  return false;
}

namespace {

// yaml-cpp tokenizes a whole flow collection before it reports the collection's first event
// (every '[' may be a simple key until its ']' is seen), so a megabyte of '[' costs about 250 MB
// and half a second before any event handler could object. This scan rejects such input first.
//
// The scan follows just enough of YAML's lexical structure to not count brackets that are text:
// comments ('#' after whitespace), quoted scalars, block scalars ('|' or '>' lines and the more
// indented lines after them), and, outside flow collections, brackets that are not at the start
// of a node (a plain scalar such as "x[1]"). Losing track only makes it count fewer brackets.
// The lexical scan behind check_flow_depth() and unclosed_flow(): calls on(c, line, column,
// offset) for every '[', '{', ']' or '}' that opens or closes a flow collection, skipping
// comments, quoted scalars and block scalars; a true return stops the scan.
template <class OnBracket>
void scan_flow_brackets(std::string_view text, OnBracket on) {
  const std::size_t n = text.size();
  std::size_t depth = 0;
  std::uint32_t line = 1;
  std::size_t line_start = 0;
  std::size_t indent = 0;  // leading spaces of the current line
  bool line_blank = true;  // nothing but whitespace so far on this line
  char last_sig = 0;       // last non-space character on this line (0: none yet)
  char prev = '\n';
  std::optional<std::size_t> block_scalar_indent;  // skipping a block scalar's lines

  std::size_t i = 0;
  auto newline = [&](std::size_t next) {
    ++line;
    line_start = next;
    indent = 0;
    line_blank = true;
    last_sig = 0;
    prev = '\n';
  };
  while (i < n) {
    const char c = text[i];
    if (c == '\n') {
      newline(i + 1);
      ++i;
      // A block scalar's content is every following line that is blank or more indented than
      // the line holding the '|' or '>'.
      while (block_scalar_indent && i < n) {
        std::size_t j = i;
        while (j < n && text[j] == ' ') ++j;
        const bool blank = j >= n || text[j] == '\n' || text[j] == '\r';
        if (!blank && j - i <= *block_scalar_indent) {
          block_scalar_indent.reset();
          break;
        }
        while (j < n && text[j] != '\n') ++j;
        if (j >= n) return;
        i = j + 1;
        newline(i);
      }
      continue;
    }
    if (c == ' ' || c == '\t' || c == '\r') {
      if (line_blank && c == ' ') ++indent;
      prev = c;
      ++i;
      continue;
    }
    const bool after_space = is_space(prev);
    // Where a node may begin: anywhere a token may begin inside a flow collection; at the start
    // of a line or after "- ", "? ", ": " outside one.
    const bool node_start =
        depth > 0 ? (after_space || prev == '[' || prev == '{' || prev == ',' || prev == ':')
                  : (line_blank ||
                     (after_space && (last_sig == '-' || last_sig == '?' || last_sig == ':')));
    if (c == '#' && after_space) {
      while (i < n && text[i] != '\n') ++i;
      continue;
    }
    line_blank = false;
    last_sig = c;
    prev = c;
    if ((c == '"' || c == '\'') && node_start) {
      std::size_t j = i + 1;
      bool closed = false;
      for (; j < n; ++j) {
        if (c == '"' && text[j] == '\\') {
          ++j;
        } else if (text[j] == c) {
          if (c == '\'' && j + 1 < n && text[j + 1] == '\'') {
            ++j;
          } else {
            closed = true;
            break;
          }
        }
      }
      if (!closed) return;
      for (std::size_t k = i; k < j; ++k) {
        if (text[k] == '\n') {
          ++line;
          line_start = k + 1;
        }
      }
      i = j + 1;
      continue;
    }
    if (depth == 0 && node_start && (c == '|' || c == '>')) {
      block_scalar_indent = indent;
      while (i < n && text[i] != '\n') ++i;
      continue;
    }
    if ((c == '[' || c == '{') && (depth > 0 || node_start)) {
      ++depth;
      if (on(c, line, static_cast<std::uint32_t>(i - line_start + 1), i)) return;
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
      if (on(c, line, static_cast<std::uint32_t>(i - line_start + 1), i)) return;
    }
    ++i;
  }
}

}  // namespace

std::optional<ScanProblem> check_flow_depth(std::string_view text, std::size_t max_depth) {
  std::size_t depth = 0;
  std::optional<ScanProblem> problem;
  scan_flow_brackets(text, [&](char c, std::uint32_t line, std::uint32_t column, std::size_t) {
    if (c == ']' || c == '}') {
      --depth;
      return false;
    }
    if (++depth <= max_depth) return false;
    problem = ScanProblem{line, column,
                          "nesting is deeper than " + std::to_string(max_depth) + " levels"};
    return true;
  });
  return problem;
}

std::optional<ScanProblem> unclosed_flow(std::string_view text, std::size_t before) {
  std::vector<ScanProblem> open;
  scan_flow_brackets(text,
                     [&](char c, std::uint32_t line, std::uint32_t column, std::size_t offset) {
                       if (offset >= before) return true;
                       if (c == '[' || c == '{') {
                         open.push_back({line, column, std::string(1, c)});
                       } else if (!open.empty()) {
                         open.pop_back();
                       }
                       return false;
                     });
  if (open.empty()) return std::nullopt;
  ScanProblem innermost = open.back();
  innermost.message = "this '" + innermost.message + "' is never closed";
  return innermost;
}

}  // namespace seqc::compiler::yaml_detail
