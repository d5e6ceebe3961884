// Over USB HID an action must fit one 64-byte report: 55 55 LEN 05 04 G b i 0B tLo tHi is 11
// bytes, then 3 per servo, so 17 servos (62 bytes) fit and 18 (65 bytes) do not.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "tests/compiler/lang_test_util.hpp"

namespace seqc::compiler {
namespace {

using testing::diagnostics_of;
using testing::MemoryFiles;
using testing::messages;

// A bus robot moving servos s1..s<n> together, twice, the second step repeated three times (each
// pass cued `at: 0ms`, a marked instant, so that its three straight moves stay three actions
// rather than one across the passes).
std::string wide_dance(int servos) {
  auto step = [&](const std::string& value) {
    std::string m;
    for (int i = 1; i <= servos; ++i) {
      m += (i > 1 ? ", s" : "s") + std::to_string(i) + ": " + value;
    }
    return m;
  };
  return "robot: bus\n"
         "sequence:\n"
         "  - move: {" +
         step("400") +
         "}\n"
         "    time: 500ms\n"
         "  - repeat: 3\n"
         "    do:\n"
         "      - move: {" +
         step("+10") +
         "}\n"
         "        time: 500ms\n"
         "        at: 0ms\n";
}

CompileOutput compile_for(const std::string& text, bool over_hid) {
  MemoryFiles files;
  files.files["main.yaml"] = text;
  CompileOptions options;
  options.over_hid = over_hid;
  return compile_file("main.yaml", files, options);
}

TEST(HidActions, EighteenServosAreOneTooManyForAHidReport) {
  const CompileOutput out = compile_for(wide_dance(18), true);
  EXPECT_FALSE(out.program);
  const std::vector<std::string> expected = {
      "3:5 error: action 1 carries 18 servos, a 65-byte frame; over USB HID a frame holds at "
      "most 64 bytes, its 4-byte header included (at most 17 servos per action)",
      "7:9 error: action 2 carries 18 servos, a 65-byte frame; over USB HID a frame holds at "
      "most 64 bytes, its 4-byte header included (at most 17 servos per action); 2 more actions "
      "of this step are too wide",
  };
  EXPECT_EQ(messages(out), expected);
}

TEST(HidActions, SeventeenServosFit) {
  const CompileOutput out = compile_for(wide_dance(17), true);
  EXPECT_TRUE(out.program) << diagnostics_of(out);
  EXPECT_EQ(out.diagnostics.all().size(), 0u) << diagnostics_of(out);
}

TEST(HidActions, ASerialLinkTakesAnyFrame) {
  const CompileOutput out = compile_for(wide_dance(18), false);
  EXPECT_TRUE(out.program) << diagnostics_of(out);
}

}  // namespace
}  // namespace seqc::compiler
