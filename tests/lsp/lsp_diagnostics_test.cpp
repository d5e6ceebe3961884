// The compiler's diagnostics as LSP Diagnostic objects: ranges in UTF-16 over the token,
// severities, rule codes and notes as related information, each under its own file.
#include <gtest/gtest.h>

#include "runtime/lsp/lsp_diagnostics.hpp"

namespace seqc::lsp {
namespace {

using nlohmann::json;

TEST(LspDiagnostics, ErrorWarningAndNoteAcrossFiles) {
  SourceManager sources;
  const std::uint32_t main =
      sources.add("/p/main.yaml", "robot: xarm\n# \xC3\xA9\xF0\x9F\x98\x80 tme: 1s\n");
  const std::uint32_t inc = sources.add("/p/inc/../inc/steps.yaml", "  - move: {claw: +900}\n");
  Diagnostics ds;
  ds.error({main, 2, 10}, "unknown key 'tme' in a move step; did you mean 'time'?");
  ds.error({inc, 1, 18}, "'claw' would move to 1100 (200 +900), above its max 1000");
  ds.note({main, 1, 1}, "included from here");
  ds.warning({main, 0, 0}, "the file has no name");
  FileDiagnostics out;
  add_lsp_diagnostics(sources, ds, "/p/main.yaml", std::nullopt, out);
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out["/p/main.yaml"], json::parse(R"([
    {"range": {"start": {"line": 1, "character": 6}, "end": {"line": 1, "character": 9}},
     "severity": 1, "code": "unknown-key", "source": "seqc",
     "message": "unknown key 'tme' in a move step; did you mean 'time'?"},
    {"range": {"start": {"line": 0, "character": 0}, "end": {"line": 0, "character": 0}},
     "severity": 2, "code": "invalid-value", "source": "seqc",
     "message": "the file has no name"}
  ])"));
  EXPECT_EQ(out["/p/inc/steps.yaml"], json::parse(R"([
    {"range": {"start": {"line": 0, "character": 17}, "end": {"line": 0, "character": 21}},
     "severity": 1, "code": "out-of-limits", "source": "seqc",
     "message": "'claw' would move to 1100 (200 +900), above its max 1000",
     "relatedInformation": [{"location": {"uri": "file:///p/main.yaml",
       "range": {"start": {"line": 0, "character": 0}, "end": {"line": 0, "character": 5}}},
       "message": "included from here"}]}
  ])"));
}

TEST(LspDiagnostics, QuotedTokenAndColumnPastTheLine) {
  SourceManager sources;
  const std::uint32_t f = sources.add("a.yaml", "name: \"x y\" # c\nshort\n");
  EXPECT_EQ(lsp_range(sources, {f, 1, 7}), json::parse(R"(
    {"start": {"line": 0, "character": 6}, "end": {"line": 0, "character": 11}})"));
  EXPECT_EQ(lsp_range(sources, {f, 2, 40}), json::parse(R"(
    {"start": {"line": 1, "character": 5}, "end": {"line": 1, "character": 5}})"));
  EXPECT_EQ(lsp_range(sources, {kNoFile, 3, 3}), json::parse(R"(
    {"start": {"line": 0, "character": 0}, "end": {"line": 0, "character": 0}})"));
}

TEST(LspDiagnostics, ReadErrorIsAFileError) {
  SourceManager sources;
  Diagnostics ds;
  FileDiagnostics out;
  add_lsp_diagnostics(sources, ds, "/p/gone.yaml", std::string("/p/gone.yaml: No such file"), out);
  EXPECT_EQ(out["/p/gone.yaml"], json::parse(R"([
    {"range": {"start": {"line": 0, "character": 0}, "end": {"line": 0, "character": 0}},
     "severity": 1, "code": "file-error", "source": "seqc", "message": "/p/gone.yaml: No such file"}
  ])"));
}

}  // namespace
}  // namespace seqc::lsp
