// A guarded YAML loader: builds a small tree from yaml-cpp's event parser, with every node's
// location, and rejects hostile input with a diagnostic instead of hanging or crashing.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "base/diagnostics.hpp"
#include "base/source.hpp"

namespace seqc::compiler {

struct YamlEntry;

struct YamlNode {
  enum class Kind { Null, Scalar, Sequence, Map };
  Kind kind = Kind::Null;
  Location location;            // where the node starts
  std::string scalar;           // Scalar: the value as written (unquoted)
  bool quoted = false;          // Scalar: written in quotes (so "500" is a string, not a number)
  std::vector<YamlNode> items;  // Sequence
  // Map, in file order, keys unique. (A named pair: std::pair of the type being defined is not
  // allowed inside it, and clang refuses it; a vector of a declared struct is.)
  std::vector<YamlEntry> entries;

  bool is_map() const { return kind == Kind::Map; }
  bool is_sequence() const { return kind == Kind::Sequence; }
  bool is_scalar() const { return kind == Kind::Scalar; }
  // Map lookup by scalar key; nullptr if absent or not a map.
  const YamlNode* find(std::string_view key) const;
};

struct YamlEntry {
  YamlNode first;   // the key
  YamlNode second;  // the value
};

struct YamlLimits {
  std::size_t max_bytes = 1 << 20;  // 1 MiB per file
  std::size_t max_depth = 64;
  std::size_t max_nodes = 1 << 20;
};

// "file is N bytes; the limit is M bytes": the error for a file over YamlLimits::max_bytes.
std::string too_large_message(std::uint64_t bytes, std::size_t limit);

// Parses file `file` of `sources`. Errors (syntax, duplicate keys, anchors/aliases, tags other
// than the core schema's, several documents, NUL bytes, invalid UTF-8, size/depth/node
// limits) go to `diags`; returns nullopt when the tree cannot be trusted.
std::optional<YamlNode> load_yaml(const SourceManager& sources, std::uint32_t file,
                                  Diagnostics& diags, const YamlLimits& limits = {});

}  // namespace seqc::compiler
