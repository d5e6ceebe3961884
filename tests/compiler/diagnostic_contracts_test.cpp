// Two promises of docs/language.md ("Diagnostics"), checked on files compiled in memory with
// the expected text written here, columns counted by hand:
// - every mistake of a step is reported, each once, in the same run;
// - the caret stands under the offending token, also after a multi-byte UTF-8 character (one
//   column on screen, more bytes in the file) and after a tab (copied, so a terminal expands it
//   alike on both lines).
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "tests/compiler/lang_test_util.hpp"

namespace seqc::compiler {
namespace {

// The rendered diagnostics of one run, each with its quoted line and caret, in order.
std::vector<std::string> rendered(const CompileOutput& out) {
  std::vector<std::string> r;
  for (const Diagnostic& d : out.diagnostics.all()) r.push_back(render(d, out.sources));
  return r;
}

// The same diagnostics whatever order the compiler finds them in.
std::vector<std::string> sorted(std::vector<std::string> v) {
  std::sort(v.begin(), v.end());
  return v;
}

TEST(DiagnosticContracts, EveryMistakeOfAStepIsReportedInOneRun) {
  // Line 5 has four mistakes (an unknown servo, two positions above the limit, one of them in
  // degrees: 300deg x 375/90deg = 1250, a position that is not a number), lines 6-8 one each:
  // seven errors.
  const std::string text =
      "robot: xarm\n"
      "sequence:\n"
      "  - move: home\n"
      "    time: 1s\n"
      "  - move: {clw: 300, base: 1200, elbow: 5O0, shoulder: 300deg}\n"
      "    time: 10ms\n"
      "    ease: in-ot\n"
      "    tolerance: -1\n";
  const CompileOutput out = testing::compile_text(text);
  //          1         2         3         4         5
  // 12345678901234567890123456789012345678901234567890123456
  //   - move: {clw: 300, base: 1200, elbow: 5O0, shoulder: 300deg}
  const std::vector<std::string> expected = {
      "main.yaml:5:12: error: unknown servo 'clw' in this move; did you mean 'claw'?\n"
      "    5 |   - move: {clw: 300, base: 1200, elbow: 5O0, shoulder: 300deg}\n"
      "      |            ^\n",
      "main.yaml:5:28: error: 'base' would move to 1200, above its max 1000\n"
      "    5 |   - move: {clw: 300, base: 1200, elbow: 5O0, shoulder: 300deg}\n"
      "      |                            ^\n",
      "main.yaml:5:41: error: '5O0' is not a position; write device units (500), degrees "
      "(90deg) or a relative move (+50, -10deg)\n"
      "    5 |   - move: {clw: 300, base: 1200, elbow: 5O0, shoulder: 300deg}\n"
      "      |                                         ^\n",
      "main.yaml:5:56: error: 'shoulder' would move to 1250 (300deg), above its max 1000\n"
      "    5 |   - move: {clw: 300, base: 1200, elbow: 5O0, shoulder: 300deg}\n"
      "      |                                                        ^\n",
      "main.yaml:6:11: error: time 10ms is below the controller's minimum of 20ms per action\n"
      "    6 |     time: 10ms\n"
      "      |           ^\n",
      "main.yaml:7:11: error: unknown easing 'in-ot'; did you mean 'in-out'? (easings: linear, in, "
      "out, in-out; back, bounce, circ, cubic, elastic, expo, quad, quart, quint, sine, each with "
      "-in, -out or -in-out; cubic-bezier(x1, y1, x2, y2))\n"
      "    7 |     ease: in-ot\n"
      "      |           ^\n",
      "main.yaml:8:16: error: 'tolerance' must be a positive distance in device units or "
      "degrees, e.g. 'tolerance: 1' or 'tolerance: 0.5deg'\n"
      "    8 |     tolerance: -1\n"
      "      |                ^\n",
  };
  EXPECT_EQ(sorted(rendered(out)), sorted(expected)) << testing::diagnostics_of(out);
  EXPECT_EQ(out.diagnostics.error_count(), 7u);
  EXPECT_EQ(out.servo_program(), nullptr);
}

TEST(DiagnosticContracts, AbsurdPositionsAreSaidAsWrittenNotWrappedAround) {
  // 22 digits do not fit a 64-bit integer: rounding them would wrap to -9223372036854775808.
  const std::string arm =
      "robot: xarm\n"
      "sequence:\n"
      "  - move: {base: 9999999999999999999999, claw: 1e3deg}\n"
      "    time: 1s\n"
      "  - move: {base: -99999999999999999999999, elbow: 1000.0}\n"
      "    time: 1s\n";
  const CompileOutput out = testing::compile_text(arm);
  EXPECT_EQ(sorted(rendered(out)),
            sorted(std::vector<std::string>{
                "main.yaml:3:18: error: 'base' would move far outside its range "
                "(9999999999999999999999), above its max 1000\n"
                "    3 |   - move: {base: 9999999999999999999999, claw: 1e3deg}\n"
                "      |                  ^\n",
                "main.yaml:3:48: error: '1e3deg' is not a position; write device units (500), "
                "degrees (90deg) or a relative move (+50, -10deg)\n"
                "    3 |   - move: {base: 9999999999999999999999, claw: 1e3deg}\n"
                "      |                                                ^\n",
                "main.yaml:5:18: error: 'base' moves -99999999999999999999999 from where the "
                "robot stands, which only a reading of its servos tells: 'seqc upload --run' and "
                "'seqc play' read them first; or move 'base' to an absolute position before "
                "this\n"
                "    5 |   - move: {base: -99999999999999999999999, elbow: 1000.0}\n"
                "      |                  ^\n"}))
      << testing::diagnostics_of(out);
  // From a known position, a relative move of 23 digits is below the minimum, said as written.
  const std::string relative =
      "robot: xarm\n"
      "sequence:\n"
      "  - move: home\n"
      "    time: 1s\n"
      "  - move: {base: -99999999999999999999999}\n"
      "    time: 1s\n";
  const CompileOutput rel = testing::compile_text(relative);
  EXPECT_EQ(
      rendered(rel),
      std::vector<std::string>{"main.yaml:5:18: error: 'base' would move far outside its range "
                               "(500 -99999999999999999999999), below its min 0\n"
                               "    5 |   - move: {base: -99999999999999999999999}\n"
                               "      |                  ^\n"})
      << testing::diagnostics_of(rel);
}

TEST(DiagnosticContracts, TheCaretStandsUnderTheTokenAfterMultiByteCharactersAndTabs) {
  // Line 3: "é" is two bytes (C3 A9), so 'base''s value is at byte column 27 but at screen
  // column 26: the caret line has 25 spaces. Line 4: a tab separates the key from its value,
  // which is at column 11; the caret line repeats the 9 spaces and the tab before it.
  const std::string text =
      "robot: xarm\n"
      "sequence:\n"
      "  - move: {\xC3\xA9: 500, base: 5000}\n"
      "    time:\t5ms\n";
  const CompileOutput out = testing::compile_text(text);
  const std::vector<std::string> expected = {
      "main.yaml:3:12: error: unknown servo '\xC3\xA9' in this move\n"
      "    3 |   - move: {\xC3\xA9: 500, base: 5000}\n"
      "      |            ^\n",
      "main.yaml:3:27: error: 'base' would move to 5000, above its max 1000\n"
      "    3 |   - move: {\xC3\xA9: 500, base: 5000}\n"
      "      |                          ^\n",
      "main.yaml:4:11: error: time 5ms is below the controller's minimum of 20ms per action\n"
      "    4 |     time:\t5ms\n"
      "      |          \t^\n",
  };
  EXPECT_EQ(sorted(rendered(out)), sorted(expected)) << testing::diagnostics_of(out);
}

}  // namespace
}  // namespace seqc::compiler
