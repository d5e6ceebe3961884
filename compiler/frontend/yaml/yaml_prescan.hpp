// Private to the YAML loader: the byte-level checks that run before yaml-cpp sees a file.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace seqc::compiler::yaml_detail {

// A problem found by a pre-scan: 1-based line and byte column, and the message.
struct ScanProblem {
  std::uint32_t line = 0;
  std::uint32_t column = 0;
  std::string message;
};

// The first byte that is not allowed in a YAML file we read: the first NUL if there is one
// anywhere (then the file is not text: "not a text file (byte 0x00 at offset N)"), else the
// first of the other C0 control characters
// except tab/LF/CR, DEL, a CR not followed by LF, or invalid UTF-8 (overlong forms, surrogates,
// code points past U+10FFFF, truncated sequences).
std::optional<ScanProblem> check_bytes(std::string_view text);

// The first '[' or '{' that opens a flow collection nested more than max_depth deep, found by a
// lexical scan that skips comments, quoted scalars and block scalars. It may miss deep nesting
// (yaml-cpp's parse and the loader's depth limit still catch that) but never reports nesting
// that is not there, except in a plain scalar whose continuation line starts with 65 brackets.
std::optional<ScanProblem> check_flow_depth(std::string_view text, std::size_t max_depth);

// The innermost '[' or '{' opened before byte `before` and not closed before it, found by the
// same scan, as "this '{' is never closed" at the bracket: where yaml-cpp's "end of map flow not
// found" belongs (it notices only where the map's next token should have been, lines later).
std::optional<ScanProblem> unclosed_flow(std::string_view text, std::size_t before);

// Whether the quoted scalar starting at text[pos] (a '"' or '\'') has its closing quote.
bool quoted_scalar_closes(std::string_view text, std::size_t pos);

}  // namespace seqc::compiler::yaml_detail
