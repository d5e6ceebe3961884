// The walk's budgets, counted as it goes: fan-outs of sections and includes stop at the first
// action over the group, the first step or include over the walk's totals, and chains of
// sections or blocks at their depth limits, each with one located error naming how the walk got
// there. Every shape here would otherwise run for hours or overflow the stack.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "tests/compiler/lang_test_util.hpp"

namespace seqc::compiler {
namespace {

using testing::compile_text;
using testing::diagnostics_of;
using testing::MemoryFiles;
using testing::messages;

// Each diagnostic as "file:line:col severity: message", for walks across files.
std::vector<std::string> located(const CompileOutput& out) {
  std::vector<std::string> m;
  for (const Diagnostic& d : out.diagnostics.all()) {
    const char* sev = d.severity == Severity::Error ? "error" : "note";
    m.push_back(out.sources.path(d.location.file) + ":" + std::to_string(d.location.line) + ":" +
                std::to_string(d.location.column) + " " + sev + ": " + d.message);
  }
  return m;
}

// Sections s<first>..s<last-1>, each performing the next twice (two-digit names keep the
// columns fixed: the first performance's name at column 19, the second's at 35), and s<last>
// holding `leaf`, from line 3 on.
std::string fan_out(int first, int last, const std::string& leaf) {
  std::string text = "robot: xarm\nsections:\n";
  for (int i = first; i < last; ++i) {
    const std::string next = "s" + std::to_string(i + 1);
    text += "  s" + std::to_string(i) + ": [{section: " + next + "}, {section: " + next + "}]\n";
  }
  return text + "  s" + std::to_string(last) + ": " + leaf + "\n";
}

// Sections s0..s<n-1>, each wrapping the next in `open` ... `close`, and s<n> a move.
std::string chain(int n, const std::string& open, const std::string& close) {
  std::string text = "robot: xarm\nsections:\n";
  for (int i = 0; i < n; ++i) {
    text += "  s" + std::to_string(i) + ": [" + open + "{section: s" + std::to_string(i + 1) + "}" +
            close + "]\n";
  }
  return text + "  s" + std::to_string(n) +
         ": [{move: {claw: 600}, time: 20ms}]\nsequence:\n  - section: s0\n";
}

// Action 1,021 starts after the 1 s move and 1,019 moves of 20 ms: 1,000 + 20,380 ms = 21.38 s.
const std::string kTooMany =
    "the sequence needs at least 1021/1020 actions; a group holds at most 1,020 (4 blocks of "
    "255), and this step makes action 1,021 at 21.38 s";

TEST(WalkBudgets, ASectionFanOutStopsAtTheFirstActionOverTheGroup) {
  // 2^11 performances of a 20 ms move after one of 1 s: the 1,020th performance (the 1,019th
  // counted from 0, 01111111011 in binary: first or second performance at each level) makes
  // action 1,021.
  auto out = compile_text(fan_out(10, 21, "[{move: {claw: 600}, time: 20ms}]") +
                          "sequence:\n  - move: {claw: 600}\n    time: 1s\n  - section: s10\n");
  EXPECT_FALSE(out.program);
  EXPECT_EQ(messages(out), (std::vector<std::string>{
                               "14:9 error: " + kTooMany,
                               "13:35 note: in section 's21', performed here",
                               "12:35 note: in section 's20', performed here",
                               "11:19 note: in section 's19', performed here",
                               "10:35 note: in section 's18', performed here",
                               "9:35 note: in section 's17', performed here",
                               "8:35 note: in section 's16', performed here",
                               "7:35 note: in section 's15', performed here",
                               "6:35 note: in section 's14', performed here",
                               "5:35 note: in section 's13', performed here",
                               "4:35 note: in section 's12', performed here",
                               "3:19 note: in section 's11', performed here",
                               "18:14 note: in section 's10', performed here",
                               "16:3 note: `seqc upload --run` stores a longer dance as "
                               "consecutive groups, each started on its bar line",
                           }))
      << diagnostics_of(out);
}

TEST(WalkBudgets, AMillionPerformancesAreNotWalked) {
  // 2^20 performances: the walk stops at the 1,020th, so the count is what it had then.
  auto out = compile_text(fan_out(10, 30, "[{move: {claw: 600}, time: 20ms}]") +
                          "sequence:\n  - move: {claw: 600}\n    time: 1s\n  - section: s10\n");
  ASSERT_EQ(out.diagnostics.error_count(), 1u) << diagnostics_of(out);
  EXPECT_EQ(messages(out)[0], "23:9 error: " + kTooMany);
  // and a note for each of the 21 performances, and how a longer dance is stored
  EXPECT_EQ(out.diagnostics.all().size(), 23u);
}

TEST(WalkBudgets, FortySectionsPerformingTheNextTwiceStopWithoutActionsToo) {
  // 2^40 performances of nothing: the step budget ends the walk (each performance is a step;
  // in the walk's order step 200,001 is s47's first, performing s48).
  auto out = compile_text(fan_out(10, 50, "[]") + "sequence:\n  - section: s10\n");
  ASSERT_EQ(out.diagnostics.error_count(), 1u) << diagnostics_of(out);
  EXPECT_EQ(messages(out)[0],
            "40:9 error: the sequence walks more than 200,000 steps, each counted again every "
            "time a section, include or repeat runs it; is there a runaway fan-out of sections "
            "or includes?");
}

TEST(WalkBudgets, TheStepBudgetStopsAtTheFirstStepOverIt) {
  // Section a performs b 500 times, b holds 500 steps: with a's own step, 1 + 501 per
  // performance, so step 200,001 is b's 100th step in its 400th performance.
  std::string text = "robot: xarm\nsections:\n  a:\n";
  for (int i = 0; i < 500; ++i) text += "    - section: b\n";
  text += "  b:\n";
  for (int i = 0; i < 500; ++i) text += "    - tolerance: 1\n";
  auto out = compile_text(text + "sequence:\n  - section: a\n");
  EXPECT_EQ(messages(out),
            (std::vector<std::string>{
                "604:7 error: the sequence walks more than 200,000 steps, each counted again "
                "every time a section, include or repeat runs it; is there a runaway fan-out of "
                "sections or includes?",
                "403:16 note: in section 'b', performed here",
                "1006:14 note: in section 'a', performed here",
            }));
}

TEST(WalkBudgets, FifteenFilesEachIncludingTheNextTenTimesStopAtInclude10001) {
  // 10^14 includes: in the walk's order the 10,001st is inc14's first, reached through the
  // first includes of main and inc1..inc10, inc11's ninth, and inc12's and inc13's tenth.
  MemoryFiles files;
  std::string main = "robot: xarm\nsequence:\n";
  for (int k = 0; k < 10; ++k) main += "  - include: inc1.yaml\n";
  files.files["main.yaml"] = main;
  for (int i = 1; i < 15; ++i) {
    std::string inc = "sequence:\n";
    for (int k = 0; k < 10; ++k) inc += "  - include: inc" + std::to_string(i + 1) + ".yaml\n";
    files.files["inc" + std::to_string(i) + ".yaml"] = inc;
  }
  files.files["inc15.yaml"] = "sequence: []\n";
  auto out = compile_file("main.yaml", files);
  std::vector<std::string> expected = {
      "inc14.yaml:2:14 error: the sequence includes files more than 10,000 times, each include "
      "counted again every time a section, include or repeat runs it; is there a runaway "
      "fan-out of includes?",
      "inc13.yaml:11:14 note: included from here",
      "inc12.yaml:11:14 note: included from here",
      "inc11.yaml:10:14 note: included from here",
  };
  for (int i = 10; i >= 1; --i) {
    expected.push_back("inc" + std::to_string(i) + ".yaml:2:14 note: included from here");
  }
  expected.push_back("main.yaml:3:14 note: included from here");
  EXPECT_EQ(located(out), expected) << diagnostics_of(out);
}

TEST(WalkBudgets, SectionsPerformingSectionsStopAt64Deep) {
  auto out = compile_text(chain(1000, "", ""));
  EXPECT_EQ(messages(out), std::vector<std::string>{
                               "66:19 error: sections perform sections more than 64 deep: s0 -> "
                               "s1 -> s2 -> ... -> s62 -> s63 -> s64; is there a runaway chain "
                               "of sections?"});
}

TEST(WalkBudgets, SectionsInsideTogetherOrRepeatStopAt64Deep) {
  const std::string deep =
      "sections perform sections more than 64 deep: s0 -> s1 -> s2 -> ... -> s62 -> s63 -> s64; "
      "is there a runaway chain of sections?";
  auto together = compile_text(chain(1000, "{together: {a: [", "]}}"));
  EXPECT_EQ(messages(together), std::vector<std::string>{"66:35 error: " + deep});
  auto repeat = compile_text(chain(1000, "{repeat: 1, do: [", "]}"));
  EXPECT_EQ(messages(repeat), std::vector<std::string>{"66:36 error: " + deep});
}

TEST(WalkBudgets, BlocksInsideBlocksStopAt64Deep) {
  // Two blocks a section: block 65 is s32's `together`.
  auto out = compile_text(chain(1000, "{together: {a: [{repeat: 1, do: [", "]}]}}"));
  EXPECT_EQ(messages(out),
            std::vector<std::string>{
                "35:9 error: this 'together' nests more than 64 blocks deep ('together', 'repeat' "
                "and 'mirror' inside each other, through sections s0 -> s1 -> s2 -> ... -> s30 "
                "-> s31 -> s32); is there a runaway chain of sections or includes?"});
}

TEST(WalkBudgets, AChainJustWithinTheLimitsIsWalked) {
  // 63 sections under the main sequence's: 64 deep, every one performed.
  auto out = compile_text(chain(63, "{together: {a: [", "]}}"));
  EXPECT_EQ(out.diagnostics.error_count(), 0u) << diagnostics_of(out);
}

}  // namespace
}  // namespace seqc::compiler
