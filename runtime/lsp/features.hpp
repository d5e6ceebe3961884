// The language features of `seqc lsp` beyond diagnostics: each answers one Language Server
// Protocol 3.17 request about a choreography file from the compiler's own reading of it.
//
// The server (runtime/lsp/server.hpp) owns the JSON-RPC framing, the open documents and the
// diagnostics; for every request it does not handle itself it calls answer_feature() with the
// request's method and params, and sends back what it returns (or, for nullopt, the error
// "method not found"). A feature reads files only through `files`, which sees an open
// document's unsaved text in place of the file on disk, so hints follow what is typed.
// Every answer is the result object the protocol defines for that method (an array, a hover,
// a workspace edit, null); a position in a file that is no choreography, or a half-typed one,
// gets an empty answer, never an error or a crash.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "base/source.hpp"

namespace seqc::lsp {

struct FeatureContext {
  FileReader& files;  // open documents over the disk
  // file:// URI <-> path, as the server maps them (percent-escapes decoded).
  std::string (*uri_to_path)(std::string_view uri);
  std::string (*path_to_uri)(std::string_view path);
};

// The `capabilities` the features add to the initialize result (merged by the server):
// inlayHintProvider, hoverProvider, definitionProvider, referencesProvider, renameProvider,
// completionProvider, codeActionProvider, documentSymbolProvider and the like.
nlohmann::json feature_capabilities();

// The result for `method` with `params`, or nullopt when `method` is no feature request.
std::optional<nlohmann::json> answer_feature(std::string_view method,
                                             const nlohmann::json& params, FeatureContext& ctx);

}  // namespace seqc::lsp
