// Fuzz target: seqc's guarded YAML loader alone (load_yaml: the byte checks, the flow-depth
// prescan and yaml-cpp's event parser under the tree builder's limits). Invariants: no crash,
// hang or sanitizer report; a load that yields no tree has an error; every diagnostic and every
// node is located at line >= 1 and column >= 1, on a line the file has.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string>

#include "base/diagnostics.hpp"
#include "compiler/frontend/yaml/yaml_tree.hpp"
#include "tests/fuzz/fuzz_check.hpp"

namespace {

using seqc::Location;
using seqc::compiler::YamlNode;

void check_located(const Location& at, std::size_t lines) {
  FUZZ_CHECK(at.line >= 1 && at.line <= lines);
  FUZZ_CHECK(at.column >= 1);
}

void check_tree(const YamlNode& node, std::size_t lines, int depth) {
  FUZZ_CHECK(depth <= 65);
  check_located(node.location, lines);
  for (const YamlNode& item : node.items) check_tree(item, lines, depth + 1);
  for (const auto& entry : node.entries) {
    FUZZ_CHECK(entry.first.is_scalar());
    check_tree(entry.first, lines, depth + 1);
    check_tree(entry.second, lines, depth + 1);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  seqc::SourceManager sources;
  seqc::Diagnostics diags;
  const auto file = sources.add("fuzz.yaml", text);
  const auto root = seqc::compiler::load_yaml(sources, file, diags);
  // A file of n newlines has n + 1 lines (the last may be empty).
  const std::size_t lines =
      1 + static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
  if (!root) FUZZ_CHECK(diags.has_errors());
  for (const auto& d : diags.all()) {
    check_located(d.location, lines);
    FUZZ_CHECK(!d.message.empty());
  }
  if (root) check_tree(*root, lines, 0);
  (void)seqc::render_all(diags, sources);
  return 0;
}
