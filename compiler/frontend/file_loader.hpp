// Reads choreography files (the main one and its includes) through the FileReader into the
// SourceManager, parses each once, and remembers it by its normalised path.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include "base/diagnostics.hpp"
#include "base/source.hpp"
#include "compiler/frontend/yaml/yaml_tree.hpp"
#include "base/result.hpp"

namespace seqc::compiler {

// How deeply includes may nest before the chain is taken for a runaway.
inline constexpr std::size_t kMaxIncludeDepth = 16;

struct LoadedFile {
  std::string path;  // as shown in diagnostics
  std::uint32_t file = 0;
  std::optional<YamlNode> root;  // nullopt when the YAML could not be trusted
};

class FileLoader {
 public:
  FileLoader(FileReader& reader, SourceManager& sources, Diagnostics& diags)
      : reader_(reader), sources_(sources), diags_(diags) {}

  // The file at `path` (already resolved), loading it on first use. An error if unreadable.
  Result<const LoadedFile*> load(const std::string& path);
  // As load(), for a file named by an `include:`. Unless it parses as a choreography file (a map
  // with a 'sequence' key), its lines are withheld from diagnostics (SourceManager): an include
  // can name any readable file, and a secret's first line must not be quoted in a report.
  Result<const LoadedFile*> load_included(const std::string& path);
  // Where the aliases of every file loaded so far put copies, for "used here" notes.
  const AliasUses& alias_uses() const { return alias_uses_; }

 private:
  FileReader& reader_;
  SourceManager& sources_;
  Diagnostics& diags_;
  std::map<std::string, std::unique_ptr<LoadedFile>> files_;
  AliasUses alias_uses_;
};

// Whether the file parsed as a choreography file: a map with a 'sequence' key.
bool is_choreography(const LoadedFile& f);

// Lexically normalised path of `target` written in the file at `from` (relative to its folder).
std::string resolve_include(const std::string& from, const std::string& target);

}  // namespace seqc::compiler
