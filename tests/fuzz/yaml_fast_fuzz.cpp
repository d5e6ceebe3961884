// Fuzz target: the fast YAML reader alone. Invariants: no crash; when it accepts, the events
// are balanced (every start has its end, one root node) and every mark lies inside the text.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "compiler/yaml/yaml_fast.hpp"
#include "tests/fuzz/fuzz_check.hpp"

using seqc::compiler::yaml_detail::FastEvent;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const auto events = seqc::compiler::yaml_detail::fast_events(text, 64);
  if (!events) return 0;
  int depth = 0;
  int roots = 0;
  for (const FastEvent& e : *events) {
    const bool end = e.kind == FastEvent::Kind::SeqEnd || e.kind == FastEvent::Kind::MapEnd;
    if (!end) FUZZ_CHECK(e.pos <= size);
    if (depth == 0 && !end) ++roots;
    if (e.kind == FastEvent::Kind::SeqStart || e.kind == FastEvent::Kind::MapStart) ++depth;
    if (end) --depth;
    FUZZ_CHECK(depth >= 0 && depth <= 65);
    if (e.kind == FastEvent::Kind::Scalar) {
      FUZZ_CHECK(e.value.data() >= text.data() &&
                 e.value.data() + e.value.size() <= text.data() + size);
    }
  }
  FUZZ_CHECK(depth == 0);
  FUZZ_CHECK(roots == 1);
  return 0;
}
