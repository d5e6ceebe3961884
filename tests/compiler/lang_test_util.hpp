// Compiling choreographies held in memory, for the language and back-end tests.
#pragma once

#include <gtest/gtest.h>

#include <map>
#include <string>
#include <vector>

#include "compiler/compile.hpp"
#include "base/diagnostics.hpp"

namespace seqc::compiler::testing {

class MemoryFiles final : public FileReader {
 public:
  std::map<std::string, std::string> files;
  Result<std::string> read(const std::string& path) override {
    auto it = files.find(path);
    if (it == files.end()) return make_error(path + ": No such file or directory");
    return it->second;
  }
};

inline CompileOutput compile_text(const std::string& text, bool strict = false) {
  MemoryFiles files;
  files.files["main.yaml"] = text;
  return compile_file("main.yaml", files, CompileOptions{strict});
}

inline std::string diagnostics_of(const CompileOutput& out) {
  return render_all(out.diagnostics, out.sources);
}

// The program, failing the test (with the diagnostics) if there is none.
inline const ServoProgram& program_of(const CompileOutput& out) {
  static const ServoProgram empty;
  const ServoProgram* p = out.servo_program();
  EXPECT_NE(p, nullptr) << diagnostics_of(out);
  return p != nullptr ? *p : empty;
}

// Each diagnostic as "line:col severity: message", for tests that check the wording.
inline std::vector<std::string> messages(const CompileOutput& out) {
  std::vector<std::string> m;
  for (const Diagnostic& d : out.diagnostics.all()) {
    const char* sev = d.severity == Severity::Error     ? "error"
                      : d.severity == Severity::Warning ? "warning"
                                                        : "note";
    m.push_back(std::to_string(d.location.line) + ":" + std::to_string(d.location.column) + " " +
                sev + ": " + d.message);
  }
  return m;
}

}  // namespace seqc::compiler::testing
