// Fuzz target: the whole `seqc check` pipeline (load, YAML, language, timeline, fitting, back
// end) on one file held in memory. The input is main.yaml; it may include "inc.yaml", which the
// in-memory file system serves as the same bytes (so self-inclusion and cycles are reachable);
// nothing touches the disk. Invariants: no crash, hang or sanitizer report; a file without a
// program has an error; every diagnostic is located in a known file at line >= 1.
#include <cstddef>
#include <cstdint>
#include <string>

#include "base/diagnostics.hpp"
#include "compiler/compile.hpp"
#include "tests/fuzz/fuzz_check.hpp"
#include "tests/fuzz/memory_files.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  for (bool strict : {false, true}) {
    seqc::fuzz::MemoryFiles files(text);
    const seqc::compiler::CompileOutput out =
        seqc::compiler::compile_file("main.yaml", files, {strict});
    // --strict only differs when there are warnings; compiling twice regardless halved the
    // fuzzer's speed on valid files (fitting dominates).
    if (!strict && out.diagnostics.warning_count() == 0) {
      FUZZ_CHECK(out.program.has_value() != out.diagnostics.has_errors(false));
      continue;
    }
    FUZZ_CHECK(out.program.has_value() != out.diagnostics.has_errors(strict));
    for (const seqc::Diagnostic& d : out.diagnostics.all()) {
      FUZZ_CHECK(d.location.file < out.sources.file_count());
      FUZZ_CHECK(d.location.line >= 1);
      FUZZ_CHECK(!d.message.empty());
    }
    (void)seqc::render_all(out.diagnostics, out.sources, strict);
  }
  return 0;
}
