// Fuzz target, differential: whenever the fast YAML reader accepts an input, yaml-cpp must
// accept it too and report exactly the same events (kinds, values, byte offsets, lines and
// columns), so the tree the loader builds cannot depend on which reader ran. When the fast
// reader declines, the loader uses yaml-cpp alone and nothing is compared.
#include <cstddef>
#include <cstdint>
#include <string>

#include "tests/compiler/yaml_events.hpp"
#include "tests/fuzz/fuzz_check.hpp"

using namespace seqc::compiler::yaml_detail;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const auto fast = fast_events(text, 64);
  if (!fast) return 0;
  const YamlCppEvents cpp = yaml_cpp_events(text);
  FUZZ_CHECK(cpp.error.empty());
  FUZZ_CHECK(describe(from_fast(*fast)) == describe(cpp.events));
  return 0;
}
