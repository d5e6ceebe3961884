// The compiler's diagnostics as LSP `Diagnostic` objects, grouped by the file they are in.
//
// Each error and warning becomes {range, severity (1 error, 2 warning), code (its rule id,
// base/diagnostic_rules.hpp), source "seqc", message}; the notes that follow it become its
// relatedInformation (location and message). The range starts at the diagnostic's column
// (bytes in the compiler, UTF-16 code units here) and covers the token there (a key, a value,
// a quoted string), or is empty at that column when no token starts there. A diagnostic with
// no line, or in no file, is at the start of the file compiled.
#pragma once

#include <map>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "base/diagnostics.hpp"
#include "base/source.hpp"

namespace seqc::lsp {

// Normal path (documents.hpp) -> array of LSP Diagnostic objects.
using FileDiagnostics = std::map<std::string, nlohmann::json>;

// The LSP range of the token at `at` in `sources` (see above).
nlohmann::json lsp_range(const SourceManager& sources, const Location& at);

// Adds the diagnostics of one compile of `main_path` (its sources and diagnostics, or the
// error that kept it from being read) to `into`, each under the file it is in.
void add_lsp_diagnostics(const SourceManager& sources, const Diagnostics& diagnostics,
                         const std::string& main_path, const std::optional<std::string>& read_error,
                         FileDiagnostics& into);

}  // namespace seqc::lsp
