// Hostile YAML: every input gets a clear diagnostic, quickly, without a hang or a crash.
// The inputs live in tests/compiler/hostile/; the big ones are generated here.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>

#include "base/diagnostics.hpp"
#include "compiler/frontend/yaml/yaml_tree.hpp"

namespace seqc::compiler {
namespace {

std::string read_hostile(const std::string& name) {
  std::ifstream in(std::string(SEQC_SOURCE_DIR) + "/tests/compiler/hostile/" + name,
                   std::ios::binary);
  EXPECT_TRUE(in.good()) << name;
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

struct Loaded {
  bool ok = false;
  std::string rendered;
  double milliseconds = 0;
};

Loaded load(const std::string& path, std::string text, const YamlLimits& limits = {}) {
  SourceManager sources;
  Diagnostics diags;
  const auto file = sources.add(path, std::move(text));
  const auto start = std::chrono::steady_clock::now();
  const auto root = load_yaml(sources, file, diags, limits);
  const auto end = std::chrono::steady_clock::now();
  Loaded out;
  out.ok = root.has_value();
  out.rendered = render_all(diags, sources);
  out.milliseconds = std::chrono::duration<double, std::milli>(end - start).count();
  return out;
}

Loaded load_hostile(const std::string& name) { return load(name, read_hostile(name)); }

std::string first_line(const std::string& s) { return s.substr(0, s.find('\n') + 1); }

TEST(YamlHostile, NulByte) {
  const auto r = load_hostile("nul_byte.yaml");
  EXPECT_FALSE(r.ok);
  // "name: walk\n" is 11 bytes and "steps: [a" 9 more: the NUL is byte 20, line 2 column 10.
  // The line holding it is not quoted, so the file's bytes never reach a terminal.
  EXPECT_EQ(r.rendered, "nul_byte.yaml:2:10: error: not a text file (byte 0x00 at offset 20)\n");
}

TEST(YamlHostile, ABinaryFileIsOneErrorWhateverComesBeforeItsFirstNul) {
  // A PNG's signature: 0x89 (invalid UTF-8), "\r\n", 0x1A and "\n" come before the first NUL
  // at offset 8 (line 3, column 1); the file is named for what it is, not its first odd byte.
  const std::string png("\x89PNG\r\n\x1a\n\0\0\0\rIHDR", 16);
  const auto r = load("logo.png", png);
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.rendered, "logo.png:3:1: error: not a text file (byte 0x00 at offset 8)\n");
}

TEST(YamlHostile, ALineThatIsNotTextIsNeverQuoted) {
  // An escape sequence (ESC [ 2 J clears a terminal) and invalid UTF-8 are reported with their
  // place, but their lines are left out; a line of plain UTF-8 text is still quoted.
  EXPECT_EQ(load("esc.yaml", "name: x\x1b[2J\n").rendered,
            "esc.yaml:1:8: error: control character U+001B is not allowed in YAML\n");
  EXPECT_EQ(load("latin1.yaml", "name: caf\xe9\n").rendered,
            "latin1.yaml:1:10: error: invalid UTF-8 (byte 0xE9)\n");
  SourceManager sources;
  const auto file = sources.add("utf8.yaml", "name: caf\xc3\xa9 \t!\n");
  EXPECT_EQ(render(Diagnostic{Severity::Error, Location{file, 1, 7}, "m"}, sources),
            "utf8.yaml:1:7: error: m\n"
            "    1 | name: caf\xc3\xa9 \t!\n"
            "      |       ^\n");
  // ... and the same file with a C1 control character (U+009B, a terminal's CSI) is not.
  const auto c1 = sources.add("c1.yaml",
                              "name: \xc2\x9b"
                              "2J\n");
  EXPECT_EQ(render(Diagnostic{Severity::Error, Location{c1, 1, 7}, "m"}, sources),
            "c1.yaml:1:7: error: m\n");
}

TEST(YamlHostile, InvalidUtf8ReportsTheFirstBadByte) {
  const auto r = load_hostile("invalid_utf8.yaml");
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(first_line(r.rendered), "invalid_utf8.yaml:2:11: error: invalid UTF-8 (byte 0xC3)\n");
  EXPECT_EQ(first_line(load_hostile("surrogate_utf8.yaml").rendered),
            "surrogate_utf8.yaml:1:4: error: invalid UTF-8 (byte 0xED)\n");
}

TEST(YamlHostile, ControlCharactersAndLoneCarriageReturns) {
  EXPECT_EQ(first_line(load_hostile("control_char.yaml").rendered),
            "control_char.yaml:1:4: error: control character U+001B is not allowed in YAML\n");
  EXPECT_EQ(first_line(load_hostile("lone_cr.yaml").rendered),
            "lone_cr.yaml:1:5: error: carriage return without a line feed (only LF and CRLF "
            "line ends are read)\n");
}

TEST(YamlHostile, ByteOrderMarkIsSkippedAndColumnsStillCountIt) {
  const auto r = load_hostile("bom_then_error.yaml");
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(first_line(r.rendered),
            "bom_then_error.yaml:1:7: error: invalid YAML: illegal flow end\n");
}

TEST(YamlHostile, AnchorsAndAliases) {
  // Aliases are copies (yaml_anchors_test.cpp has the details); these are the hostile ones.
  const auto anchor = load_hostile("anchor.yaml");
  EXPECT_TRUE(anchor.ok);
  EXPECT_EQ(anchor.rendered, "");
  EXPECT_EQ(load_hostile("alias_undefined.yaml").rendered,
            "alias_undefined.yaml:1:4: error: undefined alias '*nothing' (no anchor '&nothing' "
            "before it)\n"
            "    1 | a: *nothing\n"
            "      |    ^\n");
  EXPECT_EQ(first_line(load_hostile("cycle.yaml").rendered),
            "cycle.yaml:1:5: error: alias '*a' is inside the node it refers to (a node cannot "
            "contain itself)\n");
  // Ten levels of three aliases expand to 3^10 = 59,049 "lol"s: within the budget, so read.
  const auto laughs = load_hostile("billion_laughs.yaml");
  EXPECT_TRUE(laughs.ok);
  EXPECT_EQ(laughs.rendered, "");
  std::printf("[ measured ] billion_laughs.yaml (59,049 leaves) read in %.3f ms\n",
              laughs.milliseconds);
}

TEST(YamlHostile, SecondDocument) {
  EXPECT_EQ(load_hostile("two_documents.yaml").rendered,
            "two_documents.yaml:2:1: error: more than one document in the file ('---' starts a "
            "second one)\n"
            "    2 | ---\n"
            "      | ^\n");
}

// yaml-cpp 0.7.0 reports endless documents for a ',' it cannot place (see yaml_tree.cpp).
TEST(YamlHostile, StrayCommaThatHangsYamlCpp) {
  EXPECT_EQ(load_hostile("lone_comma.yaml").rendered,
            "lone_comma.yaml:1:1: error: unexpected ',' after the end of the document\n"
            "    1 | ,\n"
            "      | ^\n");
  EXPECT_EQ(first_line(load_hostile("trailing_comma.yaml").rendered),
            "trailing_comma.yaml:3:1: error: unexpected ',' after the end of the document\n");
  EXPECT_EQ(first_line(load_hostile("flow_then_comma.yaml").rendered),
            "flow_then_comma.yaml:1:8: error: unexpected ',' after the end of the document\n");
}

TEST(YamlHostile, Tags) {
  EXPECT_EQ(load_hostile("binary_tag.yaml").rendered,
            "binary_tag.yaml:1:7: error: tag '!!binary' is not supported\n"
            "    1 | data: !!binary aGVsbG8=\n"
            "      |       ^\n");
  // Every tag is reported in one run; the tree is still returned (a collected error).
  const auto r = load_hostile("other_tags.yaml");
  EXPECT_TRUE(r.ok);
  EXPECT_EQ(r.rendered,
            "other_tags.yaml:1:4: error: tag '!servo' is not supported\n"
            "    1 | a: !servo 3\n"
            "      |    ^\n"
            "other_tags.yaml:2:4: error: tag '!!int' is not supported\n"
            "    2 | b: !!int 4\n"
            "      |    ^\n"
            "other_tags.yaml:3:4: error: tag '!<tag:example.com,2024:x>' is not supported\n"
            "    3 | c: !<tag:example.com,2024:x> 5\n"
            "      |    ^\n");
  EXPECT_EQ(first_line(load_hostile("tag_at_end.yaml").rendered),
            "tag_at_end.yaml:1:1: error: tag '!!binary' is not supported\n");
}

TEST(YamlHostile, DuplicateKeysPointAtBothDefinitions) {
  EXPECT_EQ(load_hostile("duplicate_key.yaml").rendered,
            "duplicate_key.yaml:3:1: error: duplicate key 'name'\n"
            "    3 | name: b\n"
            "      | ^\n"
            "duplicate_key.yaml:1:1: note: first defined here\n"
            "    1 | name: a\n"
            "      | ^\n");
  // Quoting does not make a different key.
  EXPECT_EQ(first_line(load_hostile("duplicate_key_flow.yaml").rendered),
            "duplicate_key_flow.yaml:1:14: error: duplicate key 'a'\n");
}

TEST(YamlHostile, KeysMustBeScalars) {
  EXPECT_EQ(first_line(load_hostile("complex_key.yaml").rendered),
            "complex_key.yaml:1:3: error: map keys must be scalars, not a sequence\n");
  EXPECT_EQ(first_line(load_hostile("null_key.yaml").rendered),
            "null_key.yaml:2:1: error: map key is empty or null\n");
}

TEST(YamlHostile, SyntaxErrorsKeepYamlCppsMark) {
  EXPECT_EQ(load_hostile("syntax_error.yaml").rendered,
            "syntax_error.yaml:1:5: error: invalid YAML: illegal map value\n"
            "    1 | a: b: c\n"
            "      |     ^\n");
  // An unclosed bracket is said at the bracket, not where yaml-cpp noticed it (line 2).
  EXPECT_EQ(first_line(load_hostile("unclosed_flow.yaml").rendered),
            "unclosed_flow.yaml:1:8: error: invalid YAML: this '[' is never closed\n");
  EXPECT_EQ(first_line(load_hostile("unterminated_quote.yaml").rendered),
            "unterminated_quote.yaml:1:4: error: unterminated quoted string\n");
}

TEST(YamlHostile, AnUnclosedBraceIsSaidAtTheBrace) {
  // yaml-cpp notices the missing '}' at "time" on the next line; the caret goes to the '{'.
  EXPECT_EQ(load("move.yaml", "sequence:\n  - move: {base: 500\n    time: 1s\n").rendered,
            "move.yaml:2:11: error: invalid YAML: this '{' is never closed\n"
            "    2 |   - move: {base: 500\n"
            "      |           ^\n");
  // At the end of the file too; a brace in a comment or a quoted scalar is not counted, and
  // the innermost bracket still open is the one named.
  EXPECT_EQ(load("end.yaml", "a: {b: \"{\", c: [1, 2], d: {e: 1}  # {\n").rendered,
            "end.yaml:1:4: error: invalid YAML: this '{' is never closed\n"
            "    1 | a: {b: \"{\", c: [1, 2], d: {e: 1}  # {\n"
            "      |    ^\n");
  EXPECT_EQ(first_line(load("seq.yaml", "a: {b: [1, 2\n").rendered),
            "seq.yaml:1:8: error: invalid YAML: this '[' is never closed\n");
  // A byte-order mark counts in line 1's columns, as everywhere else.
  EXPECT_EQ(first_line(load("bom.yaml",
                            "\xEF\xBB\xBF"
                            "a: {b: 1\n")
                           .rendered),
            "bom.yaml:1:7: error: invalid YAML: this '{' is never closed\n");
}

TEST(YamlHostile, DeepNesting) {
  EXPECT_EQ(first_line(load_hostile("deep_flow.yaml").rendered),
            "deep_flow.yaml:1:65: error: nesting is deeper than 64 levels\n");
  EXPECT_EQ(first_line(load_hostile("deep_block.yaml").rendered),
            "deep_block.yaml:1:129: error: nesting is deeper than 64 levels\n");
}

TEST(YamlHostile, TenThousandOpenBrackets) {
  const auto r = load("deep.yaml", std::string(10000, '['));
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(first_line(r.rendered), "deep.yaml:1:65: error: nesting is deeper than 64 levels\n");
  std::printf("[ measured ] 10,000 '[' rejected in %.3f ms\n", r.milliseconds);
}

TEST(YamlHostile, AliasBombIsRejectedAtTheAliasThatPassesTheBudget) {
  // 100,000 aliases of a 3-node anchor: 87,381 fit in the 262,144 nodes aliases may copy; the
  // next, at column 7 + 4 * 87,381, is refused before it is copied.
  std::string bomb = "base: &a [x, y]\nall: [";
  for (int i = 0; i < 100000; ++i) bomb += i == 0 ? "*a" : ", *a";
  bomb += "]\n";
  auto r = load("bomb.yaml", bomb);
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(first_line(r.rendered),
            "bomb.yaml:2:349531: error: aliases expand to more than 262144 nodes (a YAML "
            "\"billion laughs\"?)\n");
  std::printf("[ measured ] 100,000-alias bomb (%zu bytes) rejected in %.3f ms\n", bomb.size(),
              r.milliseconds);

  // The same aliases with no anchor at all: stops at the first alias.
  std::string aliases = "all: [";
  for (int i = 0; i < 100000; ++i) aliases += i == 0 ? "*a" : ", *a";
  aliases += "]\n";
  r = load("aliases.yaml", aliases);
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(first_line(r.rendered),
            "aliases.yaml:1:7: error: undefined alias '*a' (no anchor '&a' before it)\n");
}

TEST(YamlHostile, OversizedFileIsRejectedWithoutParsing) {
  // Five MiB of text that would be a syntax error at line 1 if it were parsed.
  std::string big = "a: b: c\n";
  big.resize(5u << 20, '#');
  const auto r = load("big.yaml", big);
  EXPECT_FALSE(r.ok);
  // Located at the start of the file (every diagnostic has a place), quoting its first line.
  EXPECT_EQ(r.rendered,
            "big.yaml:1:1: error: file is 5242880 bytes; the limit is 1048576 bytes\n"
            "    1 | a: b: c\n"
            "      | ^\n");
  std::printf("[ measured ] 5 MiB file rejected in %.3f ms\n", r.milliseconds);
}

TEST(YamlHostile, NodeLimitStopsEarly) {
  YamlLimits limits;
  limits.max_nodes = 1000;
  std::string many;
  for (int i = 0; i < 5000; ++i) many += "- " + std::to_string(i) + "\n";
  const auto r = load("many.yaml", many, limits);
  EXPECT_FALSE(r.ok);
  // The sequence is node 1, so node 1001 is the 1000th item, on line 1000.
  EXPECT_EQ(first_line(r.rendered),
            "many.yaml:1000:3: error: the file has more than 1000 YAML nodes\n");
}

// How long the worst inputs take is measured by tests/bench/yaml_worst_bench.
}  // namespace
}  // namespace seqc::compiler
