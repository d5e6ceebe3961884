// Golden tests of what a person reads: the diagnostic layout is fixed here, byte for byte.
#include "base/diagnostics.hpp"
#include "base/terminal_text.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

namespace seqc::compiler {
namespace {

class RenderTest : public ::testing::Test {
 protected:
  RenderTest() {
    walk_ = sources_.add("walk.yaml",
                         "name: walk\n"
                         "steps:\n"
                         "  - pose: stand\n"
                         "    servos:\n"
                         "      tme: 500ms\n");
  }
  SourceManager sources_;
  std::uint32_t walk_ = 0;
};

TEST_F(RenderTest, ErrorWithLineNumberGutterAndCaret) {
  const Diagnostic d{Severity::Error, {walk_, 5, 7}, "unknown key 'tme'; did you mean 'time'?"};
  EXPECT_EQ(render(d, sources_),
            "walk.yaml:5:7: error: unknown key 'tme'; did you mean 'time'?\n"
            "    5 |       tme: 500ms\n"
            "      |       ^\n");
}

TEST_F(RenderTest, TwoDigitLineNumbersAlign) {
  std::string text;
  for (int i = 1; i < 12; ++i) text += fmt::format("a{}: 1\n", i);
  text += "      tme: 500ms\n";
  const auto f = sources_.add("walk.yaml", text);
  const Diagnostic d{Severity::Error, {f, 12, 7}, "unknown key 'tme'; did you mean 'time'?"};
  EXPECT_EQ(render(d, sources_),
            "walk.yaml:12:7: error: unknown key 'tme'; did you mean 'time'?\n"
            "   12 |       tme: 500ms\n"
            "      |       ^\n");
}

TEST_F(RenderTest, WideLineNumbersWidenTheGutter) {
  std::string text(123456, '\n');
  text += "x: 1\n";
  const auto f = sources_.add("big.yaml", text);
  const Diagnostic d{Severity::Error, {f, 123457, 4}, "bad"};
  EXPECT_EQ(render(d, sources_),
            "big.yaml:123457:4: error: bad\n"
            " 123457 | x: 1\n"
            "        |    ^\n");
}

TEST_F(RenderTest, WarningAndNote) {
  Diagnostics ds;
  ds.warning({walk_, 1, 7}, "name is not used");
  ds.note({walk_, 3, 5}, "first defined here");
  EXPECT_EQ(render_all(ds, sources_),
            "walk.yaml:1:7: warning: name is not used\n"
            "    1 | name: walk\n"
            "      |       ^\n"
            "walk.yaml:3:5: note: first defined here\n"
            "    3 |   - pose: stand\n"
            "      |     ^\n");
}

TEST_F(RenderTest, StrictRendersWarningsAsErrors) {
  const Diagnostic w{Severity::Warning, {walk_, 1, 1}, "name is not used"};
  EXPECT_EQ(render(w, sources_, true),
            "walk.yaml:1:1: error: name is not used [--strict]\n"
            "    1 | name: walk\n"
            "      | ^\n");
  const Diagnostic n{Severity::Note, {walk_, 1, 1}, "here"};
  EXPECT_EQ(render(n, sources_, true).substr(0, 26), "walk.yaml:1:1: note: here\n");
  const Diagnostic e{Severity::Error, {walk_, 1, 1}, "bad"};
  EXPECT_EQ(render(e, sources_, true).substr(0, 26), "walk.yaml:1:1: error: bad\n");
}

TEST_F(RenderTest, TabsAreCopiedIntoTheCaretLine) {
  const auto f = sources_.add("tabs.yaml", "a:\n\t\tb: x\n");
  const Diagnostic d{Severity::Error, {f, 2, 6}, "bad value"};
  EXPECT_EQ(render(d, sources_),
            "tabs.yaml:2:6: error: bad value\n"
            "    2 | \t\tb: x\n"
            "      | \t\t   ^\n");
}

TEST_F(RenderTest, MultiByteCharactersTakeOneCaretColumn) {
  // Columns count bytes; "é" is two bytes but one column on screen.
  const auto f = sources_.add("u.yaml",
                              "\xEF\xBB\xBF"
                              "caf\xC3\xA9: ]\n");
  const Diagnostic d{Severity::Error, {f, 1, 11}, "bad"};
  EXPECT_EQ(render(d, sources_),
            "u.yaml:1:11: error: bad\n"
            "    1 | \xEF\xBB\xBF"
            "caf\xC3\xA9: ]\n"
            "      |       ^\n");
}

TEST_F(RenderTest, CrlfLinesAreQuotedWithoutTheCarriageReturn) {
  const auto f = sources_.add("crlf.yaml", "a: 1\r\nb: 2\r\n");
  const Diagnostic d{Severity::Error, {f, 2, 4}, "bad"};
  EXPECT_EQ(render(d, sources_),
            "crlf.yaml:2:4: error: bad\n"
            "    2 | b: 2\n"
            "      |    ^\n");
}

TEST_F(RenderTest, ColumnPastTheEndPutsTheCaretAfterTheLine) {
  const Diagnostic d{Severity::Error, {walk_, 1, 40}, "expected more"};
  EXPECT_EQ(render(d, sources_),
            "walk.yaml:1:40: error: expected more\n"
            "    1 | name: walk\n"
            "      |           ^\n");
}

TEST_F(RenderTest, LineWithoutColumnQuotesTheLineWithoutCaret) {
  const Diagnostic d{Severity::Error, {walk_, 2, 0}, "steps are empty"};
  EXPECT_EQ(render(d, sources_),
            "walk.yaml:2: error: steps are empty\n"
            "    2 | steps:\n");
}

TEST_F(RenderTest, LineZeroMeansTheWholeFile) {
  const Diagnostic d{Severity::Error, {walk_, 0, 0}, "file is too large"};
  EXPECT_EQ(render(d, sources_), "walk.yaml: error: file is too large\n");
}

TEST_F(RenderTest, NoFileRendersAsSeqc) {
  const Diagnostic d{Severity::Error, {kNoFile, 0, 0}, "--port is required"};
  EXPECT_EQ(render(d, sources_), "seqc: error: --port is required\n");
  const Diagnostic stale{Severity::Warning, {99, 3, 1}, "stale"};
  EXPECT_EQ(render(stale, sources_), "seqc: warning: stale\n");
}

TEST_F(RenderTest, LineBeyondTheFileIsNotQuoted) {
  const Diagnostic d{Severity::Error, {walk_, 60, 1}, "bad"};
  EXPECT_EQ(render(d, sources_), "walk.yaml:60:1: error: bad\n");
}

// A value quoted from a file cannot drive the terminal or forge a diagnostic line: its control
// characters arrive as escapes, in the message and in the path alike.
TEST_F(RenderTest, ControlCharactersInTheMessageAndPathAreEscaped) {
  const auto f = sources_.add("a\x1b]0;t\a.yaml", "name: x\n");
  const Diagnostic d{Severity::Error,
                     {f, 1, 7},
                     "unknown pose 'p\x1b[2J\nwalk.yaml:1:1: error: forged\r\x7f\xc2\x9b'"};
  EXPECT_EQ(render(d, sources_),
            "a\\x1b]0;t\\x07.yaml:1:7: error: unknown pose 'p\\x1b[2J\\nwalk.yaml:1:1: error: "
            "forged\\r\\x7f\\u009b'\n"
            "    1 | name: x\n"
            "      |       ^\n");
}

// An include that is no choreography file (it may be a secret) is located but never quoted.
TEST_F(RenderTest, WithheldLinesAreNotQuoted) {
  const auto f = sources_.add("/etc/shadow", "root:$6$hash:19000::::\n");
  sources_.withhold_lines(f);
  const Diagnostic d{Severity::Error, {f, 1, 1}, "missing 'sequence'"};
  EXPECT_EQ(render(d, sources_), "/etc/shadow:1:1: error: missing 'sequence'\n");
  EXPECT_TRUE(sources_.quotes_lines(walk_));
  EXPECT_FALSE(sources_.quotes_lines(f));
}

TEST(TerminalSafe, ShowsEveryControlCharacterAsAnEscape) {
  EXPECT_EQ(terminal_safe("plain\ttext, é and ✓ \\x41"), "plain\ttext, é and ✓ \\x41");
  EXPECT_EQ(terminal_safe("\x1b[31mred\x1b[0m"), "\\x1b[31mred\\x1b[0m");
  EXPECT_EQ(terminal_safe("a\nb\rc"), "a\\nb\\rc");
  EXPECT_EQ(terminal_safe(std::string("\0\x01\x07\x08\x1f\x7f", 6)),
            "\\x00\\x01\\x07\\x08\\x1f\\x7f");
  // C1 controls as UTF-8 (U+009B is CSI), the first printable one after them, and stray bytes.
  EXPECT_EQ(terminal_safe("\xc2\x80\xc2\x9b\xc2\x9f\xc2\xa0"), "\\u0080\\u009b\\u009f\xc2\xa0");
  EXPECT_EQ(terminal_safe("\x9b"
                          "2J \xff \xc3"),
            "\\x9b2J \\xff \\xc3");
}

TEST(Diagnostics, CountsAndStrictness) {
  Diagnostics ds;
  EXPECT_FALSE(ds.has_errors());
  EXPECT_FALSE(ds.has_errors(true));
  ds.warning({}, "w");
  ds.note({}, "n");
  EXPECT_FALSE(ds.has_errors());
  EXPECT_TRUE(ds.has_errors(true));
  EXPECT_EQ(ds.warning_count(), 1u);
  EXPECT_EQ(ds.error_count(), 0u);
  ds.error({}, "e");
  EXPECT_TRUE(ds.has_errors());
  EXPECT_EQ(ds.error_count(), 1u);
  ASSERT_EQ(ds.all().size(), 3u);
  EXPECT_EQ(ds.all()[1].severity, Severity::Note);
  EXPECT_EQ(ds.all()[2].message, "e");
}

TEST(DidYouMean, FindsOneTypo) {
  const std::vector<std::string> keys = {"name", "time", "servos", "pose", "steps"};
  EXPECT_EQ(did_you_mean("tme", keys), "time");
  EXPECT_EQ(did_you_mean("tiem", keys), "time");  // transposition is one edit
  EXPECT_EQ(did_you_mean("servo", keys), "servos");
  EXPECT_EQ(did_you_mean("srevos", keys), "servos");
  EXPECT_EQ(did_you_mean("stpes", keys), "steps");
}

TEST(DidYouMean, CaseDifferencesCostNothing) {
  const std::vector<std::string> keys = {"name", "time", "tempo", "steps"};
  // Four letters differ in case: too many edits case-sensitively, none when folded.
  EXPECT_EQ(did_you_mean("TIME", keys), "time");
  EXPECT_EQ(did_you_mean("Steps", keys), "steps");
  EXPECT_EQ(did_you_mean("TMIE", keys), "time");  // a case change and a transposition
  // A closer match ignoring case wins over a closer match respecting it.
  EXPECT_EQ(did_you_mean("TIME", {"tim", "time"}), "time");
  EXPECT_EQ(did_you_mean("TIME", {"TIMER", "time"}), "time");
  // Between two candidates equal when folded, the one matching the case wins.
  EXPECT_EQ(did_you_mean("Pose", {"pose", "Pose2", "POSE"}), "pose");
}

TEST(DidYouMean, NothingCloseMeansNoSuggestion) {
  const std::vector<std::string> keys = {"name", "time", "servos"};
  EXPECT_EQ(did_you_mean("speed", keys), "");
  EXPECT_EQ(did_you_mean("tx", keys), "");
  EXPECT_EQ(did_you_mean("", keys), "");
  EXPECT_EQ(did_you_mean("time", {}), "");
  EXPECT_EQ(did_you_mean(std::string(100000, 'x'), keys), "");
}

TEST(DidYouMean, ThresholdGrowsWithLength) {
  // 9 letters allow 3 edits, 8 allow 2, 6 allow 2, 5 allow 1.
  EXPECT_EQ(did_you_mean("dxrxtxion", {"duration"}), "duration");
  EXPECT_EQ(did_you_mean("dxrxtxon", {"duration"}), "");
  EXPECT_EQ(did_you_mean("sxrxos", {"servos"}), "servos");
  EXPECT_EQ(did_you_mean("sxrxo", {"servo"}), "");
}

TEST(DidYouMean, CaseDifferencesAreCloseAndTiesAreDeterministic) {
  EXPECT_EQ(did_you_mean("Time", {"time"}), "time");
  // Equal case-insensitive distance: the one matching the case as written wins.
  EXPECT_EQ(did_you_mean("Sped", {"speed", "Spend"}), "Spend");
  EXPECT_EQ(did_you_mean("Sped", {"Spend", "speed"}), "Spend");
  // Fully tied: the alphabetically first, whatever the candidate order.
  EXPECT_EQ(did_you_mean("cat", {"cut", "bat"}), "bat");
  EXPECT_EQ(did_you_mean("cat", {"bat", "cut"}), "bat");
}

TEST(DidYouMean, ExactMatchIsNotSuggested) { EXPECT_EQ(did_you_mean("time", {"time"}), ""); }

}  // namespace
}  // namespace seqc::compiler
