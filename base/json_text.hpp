// JSON string literals for everything seqc writes as JSON (listings, diagnostics, SARIF):
// quotes, backslashes and control characters escaped, and bytes that are not valid UTF-8
// (a hostile file's text quoted in a message) replaced by U+FFFD, so the output always parses.
#pragma once

#include <string>
#include <string_view>

namespace seqc {

std::string json_string(std::string_view s);

}  // namespace seqc
