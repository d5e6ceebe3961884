// Private to the YAML loader: a fast reader for the plain subset of YAML that choreography files
// are nearly always written in, producing exactly the events yaml-cpp's parser would report.
//
// The subset: block maps and block sequences (including compact "- key: v" and indentless
// "key:\n- item" forms), single-line flow maps and sequences, plain scalars of letters, digits
// and "_-.+/" with single-line inner spaces, comments, blank lines, LF line ends. Anything else
// (quotes, tags, anchors, nulls written as nothing, multi-line scalars, document markers, tabs,
// CR, a syntax error of any kind, nesting deeper than max_depth) makes fast_events return
// nullopt, and the loader parses the file with yaml-cpp as before. So every diagnostic yaml-cpp
// or the loader gives is unchanged: on accepted input the same events reach the same handler.
// tests/compiler/yaml_fast_test.cpp compares the events with yaml-cpp's on many inputs.
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

namespace seqc::compiler::yaml_detail {

struct FastEvent {
  enum class Kind : std::uint8_t { Null, Scalar, SeqStart, SeqEnd, MapStart, MapEnd };
  Kind kind = Kind::Null;
  // yaml-cpp's mark of the node (0-based byte offset, line and column); unset for *End.
  std::uint32_t pos = 0;
  std::uint32_t line = 0;
  std::uint32_t column = 0;
  std::string_view value;  // Scalar: a slice of the text
};

// The events of the one document in `text` (a file without its byte-order mark), or nullopt if
// the text is not entirely within the subset.
std::optional<std::vector<FastEvent>> fast_events(std::string_view text, std::size_t max_depth);

}  // namespace seqc::compiler::yaml_detail
