// A guarded YAML loader: builds a small tree from yaml-cpp's event parser, with every node's
// location, and rejects hostile input with a diagnostic instead of hanging or crashing. Anchors,
// aliases and merge keys ('<<') are resolved by copying: the tree is a tree, never shared.
#pragma once

#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <tuple>
#include <utility>
#include <vector>

#include "base/diagnostics.hpp"
#include "base/source.hpp"

namespace seqc::compiler {

struct YamlEntry;

struct YamlNode {
  enum class Kind { Null, Scalar, Sequence, Map };
  Kind kind = Kind::Null;
  Location location;  // where the node starts
  // For a node an alias copied here: where that alias is (line 0: the node is written here).
  // A copy keeps the anchored node's `location`, so a mistake in it is said at the anchor and
  // this is where it was used. For aliases inside anchored nodes, the innermost alias.
  Location used_at;
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
  std::size_t max_nodes = 1 << 20;  // nodes written in the file
  // Nodes aliases may copy in all, checked before each copy (a YAML "billion laughs" file
  // would grow exponentially): nearly four times what a full program of 1,020 steps copies
  // when every step merges in a 32-servo pose (65 nodes).
  std::size_t max_alias_nodes = 1 << 18;
};

// Where aliases put copies: for the location of each node inside a copy, the aliases that
// copied it (YamlNode::used_at, each once, in file order of the trees added), so a diagnostic
// said at an anchored node can name the places it was used.
class AliasUses {
 public:
  // Records every copied node of `root` (a file's tree).
  void add(const YamlNode& root);
  // The aliases that copied a node at `at`; empty if none did.
  const std::vector<Location>& sites(Location at) const;

 private:
  std::map<std::tuple<std::uint32_t, std::uint32_t, std::uint32_t>, std::vector<Location>> sites_;
};

// "file is N bytes; the limit is M bytes": the error for a file over YamlLimits::max_bytes.
std::string too_large_message(std::uint64_t bytes, std::size_t limit);

// Parses file `file` of `sources`. Errors (syntax, duplicate keys, aliases to undefined anchors
// or inside their own anchor, misused merge keys, tags other than the core schema's, several
// documents, NUL bytes, invalid UTF-8, size/depth/node/alias-copy limits) go to `diags`;
// returns nullopt when the tree cannot be trusted.
std::optional<YamlNode> load_yaml(const SourceManager& sources, std::uint32_t file,
                                  Diagnostics& diags, const YamlLimits& limits = {});

// "empty", "a single value", "a list", "a map": what a node is, for "..., not a list" messages.
std::string_view kind_name(const YamlNode& node);

}  // namespace seqc::compiler
