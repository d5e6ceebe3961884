// Fuzz target, differential: whenever the fast YAML reader accepts an input, yaml-cpp must
// accept it too and report exactly the same events (kinds, values, byte offsets, lines and
// columns), so the tree the loader builds cannot depend on which reader ran. When the fast
// reader declines, the loader uses yaml-cpp alone and nothing is compared.
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

#include "tests/compiler/yaml_events.hpp"
#include "tests/fuzz/fuzz_check.hpp"

using namespace seqc::compiler::yaml_detail;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const auto fast = fast_events(text, 64);
  if (!fast) return 0;
  Recorder recorder;
  bool error = false;
  try {
    std::istringstream in(text);
    YAML::Parser parser(in);
    for (int i = 0; i < 2 && parser.HandleNextDocument(recorder); ++i) {
    }
  } catch (const YAML::Exception&) {
    error = true;
  } catch (const SecondDocument&) {
    error = true;
  }
  FUZZ_CHECK(!error);
  FUZZ_CHECK(describe(from_fast(*fast)) == describe(recorder.events));
  return 0;
}
