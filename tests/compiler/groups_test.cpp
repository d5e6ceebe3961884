// Servo groups (`groups: {left: [...]}`): a group's name in a move gives each member the value,
// checked per member, in poses, mirrored, in tracks and through section parameters; and the
// warning for a section of the main file that nothing performs. Expected actions and messages
// are worked out by hand from docs/language.md.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "tests/compiler/lang_test_util.hpp"

namespace seqc::compiler {
namespace {

using testing::compile_text;
using testing::diagnostics_of;
using testing::MemoryFiles;
using testing::messages;
using testing::program_of;
using T = std::vector<lsc::ServoTarget>;

// ---- groups ------------------------------------------------------------------------------------

TEST(Groups, AGroupMovesEachMemberAbsoluteOrFromItsOwnPosition) {
  auto out = compile_text(R"(robot:
  profile: bus
  servos: {lf_coxa: 1, lm_coxa: 2, lr_coxa: 3, rf_coxa: 4}
groups:
  left: [lf_coxa, lm_coxa, lr_coxa]
sequence:
  - move: {left: 500, rf_coxa: 500}
    time: 1s
  - move: {lm_coxa: 600}
    time: 1s
  - move: {left: +100}
    time: 1s
  - move: {left: 400}
    time: 1s
)");
  const ServoProgram& p = program_of(out);
  ASSERT_EQ(p.keyframes.size(), 4u) << diagnostics_of(out);
  EXPECT_EQ(p.keyframes[0].targets, T({{1, 500}, {2, 500}, {3, 500}, {4, 500}}));
  EXPECT_EQ(p.keyframes[1].targets, T({{2, 600}}));
  // Each from its own position: 500 + 100, 600 + 100, 500 + 100.
  EXPECT_EQ(p.keyframes[2].targets, T({{1, 600}, {2, 700}, {3, 600}}));
  EXPECT_EQ(p.keyframes[3].targets, T({{1, 400}, {2, 400}, {3, 400}}));
  EXPECT_EQ(diagnostics_of(out), "");
}

TEST(Groups, ALimitNamesTheMemberWithANoteWhereTheGroupListsIt) {
  auto out = compile_text(R"(robot:
  profile: bus
  servos: {lf_coxa: 1, lm_coxa: 2, lr_coxa: 3}
groups:
  left: [lf_coxa, lm_coxa, lr_coxa]
sequence:
  - move: {left: 500}
    time: 1s
  - move: {lm_coxa: 950}
    time: 1s
  - move: {left: +100}
    time: 1s
)");
  EXPECT_EQ(messages(out),
            (std::vector<std::string>{
                "11:18 error: 'lm_coxa' would move to 1050 (950 +100), above its max 1000",
                "5:19 note: 'lm_coxa' moves through group 'left', which lists it here"}));
}

TEST(Groups, MistakesInTheDefinitionAreLocated) {
  auto out = compile_text(R"(robot:
  profile: bus
  servos: {lf_coxa: 1, lm_coxa: 2}
groups:
  lf_coxa: [lm_coxa]
  s2: [lf_coxa]
  typo: [lf_coxa, lm_coxx]
  none: []
  twice: [lf_coxa, s1]
  nest: [typo]
sequence:
  - move: {typo: 500}
    time: 1s
  - move: {typoo: 500}
    time: 1s
)");
  EXPECT_EQ(messages(out),
            (std::vector<std::string>{
                "5:3 error: group 'lf_coxa' has the name of a servo; a move could not tell them "
                "apart: rename the group",
                // The bus profile's own name for id 2 is an alias of lm_coxa.
                "6:3 error: group 's2' has the name of a servo ('lm_coxa'); a move could not "
                "tell them apart: rename the group",
                "7:19 error: unknown servo 'lm_coxx' in group 'typo'; did you mean 'lm_coxa'?",
                "8:9 error: group 'none' is empty; list the servos it moves",
                "9:20 error: servo 'lf_coxa' is listed twice in group 'twice'",
                "10:10 error: 'typo' is a group; a group lists servos, so write its servos here",
                "14:12 error: unknown servo 'typoo' in this move; did you mean 'typo'?"}));
}

TEST(Groups, AServoGivenByNameAndThroughAGroupInOneMoveIsAnError) {
  auto out = compile_text(R"(robot:
  profile: bus
  servos: {lf_coxa: 1, lm_coxa: 2, rf_coxa: 3}
groups:
  left: [lf_coxa, lm_coxa]
  front: [lf_coxa, rf_coxa]
sequence:
  - move: {left: 500, lf_coxa: 400}
    time: 1s
  - move: {left: 500, front: 400}
    time: 1s
)");
  EXPECT_EQ(messages(out),
            (std::vector<std::string>{
                "8:23 error: servo 'lf_coxa' is given twice in this move: by name and through "
                "group 'left'",
                "10:23 error: servo 'lf_coxa' is given twice in this move: through groups 'left' "
                "and 'front'"}));
}

TEST(Groups, WorkInPosesMirroredInTracksAndAsSectionParameters) {
  auto out = compile_text(R"(robot:
  profile: bus
  servos: {lf_coxa: 1, lm_coxa: 2, rf_coxa: 3, rm_coxa: 4}
  mirror: {lf_coxa: rf_coxa, lm_coxa: rm_coxa}
groups:
  left: [lf_coxa, lm_coxa]
poses:
  wide: {left: 600}
sections:
  swing:
    params: {legs: left}
    steps:
      - move: {$legs: +50}
        time: 1s
sequence:
  - move: home
    time: 1s
  - move: wide
    time: 1s
  - mirror:
      - move: wide
        time: 1s
  - together:
      a:
        - section: swing
      b:
        - move: {rf_coxa: 450}
          time: 1s
)");
  const ServoProgram& p = program_of(out);
  ASSERT_EQ(p.keyframes.size(), 4u) << diagnostics_of(out);
  EXPECT_EQ(p.keyframes[0].targets, T({{1, 500}, {2, 500}, {3, 500}, {4, 500}}));
  EXPECT_EQ(p.keyframes[1].targets, T({{1, 600}, {2, 600}}));
  // Mirrored: each member onto its partner, reflected around home: 500 - (600 - 500) = 400.
  EXPECT_EQ(p.keyframes[2].targets, T({{3, 400}, {4, 400}}));
  EXPECT_EQ(p.keyframes[3].targets, T({{1, 650}, {2, 650}, {3, 450}}));
}

TEST(Groups, AMemberMovedInTwoTracksAndTooFastIsNamed) {
  auto out = compile_text(R"(robot:
  profile: bus
  servos:
    lf_coxa: {id: 1, max_speed: 1000/s}
    lm_coxa: {id: 2, max_speed: 1000/s}
groups:
  left: [lf_coxa, lm_coxa]
sequence:
  - move: {left: 500}
    time: 1s
  - move: {left: 900}
    time: 200ms
  - together:
      a:
        - move: {left: 500}
          time: 1s
      b:
        - move: {lm_coxa: 600}
          time: 1s
)");
  EXPECT_EQ(messages(out),
            (std::vector<std::string>{
                // 400 units in 0.2 s is 2000/s, twice their 1000/s.
                "11:5 warning: servos 'lf_coxa', 'lm_coxa' move 400 in 200ms at 2000/s, above "
                "their 1000/s",
                "18:11 error: 'lm_coxa' moves in two tracks, 'a' and 'b'; a servo may move in "
                "one track of a 'together' only",
                "15:11 note: 'lm_coxa' moves in track 'a' here"}));
}

// ---- sections never performed ------------------------------------------------------------------

TEST(UnperformedSections, AreWarnedAtTheirNameInTheMainFile) {
  // 'inner' is performed only from 'used', which is performed: both count. 'deadinner' is
  // performed only from 'dead', which nothing performs.
  auto out = compile_text(R"(robot: xarm
sections:
  used: [{section: inner}]
  inner: [{move: {base: +10}, time: 1s}]
  dead: [{section: deadinner}]
  deadinner: [{move: {base: +10}, time: 1s}]
sequence:
  - move: home
    time: 2s
  - section: used
)");
  EXPECT_TRUE(out.servo_program() != nullptr) << diagnostics_of(out);
  EXPECT_EQ(messages(out), (std::vector<std::string>{
                               "5:3 warning: section 'dead' is defined but never performed",
                               "6:3 warning: section 'deadinner' is defined but never performed"}));
}

TEST(UnperformedSections, NotInAnIncludedLibraryAndCountedFromIt) {
  MemoryFiles files;
  // The main file's 'wiggle' is performed only by the library (a section of a file that
  // includes it); the library's own 'spare' is for others and is not warned.
  files.files["main.yaml"] = R"(robot: xarm
sections:
  wiggle: [{move: {base: +10}, time: 1s}]
sequence:
  - move: home
    time: 2s
  - include: lib.yaml
)";
  files.files["lib.yaml"] = R"(robot: xarm
sections:
  spare: [{move: {base: -10}, time: 1s}]
sequence:
  - section: wiggle
)";
  auto out = compile_file("main.yaml", files, CompileOptions{});
  EXPECT_EQ(messages(out), std::vector<std::string>{});
}

TEST(UnperformedSections, NotAfterAnErrorWhichMayHaveKeptAPerformanceFromTheWalk) {
  auto out = compile_text(R"(robot: xarm
sections:
  nod:
    params: {by: 10}
    steps: [{move: {base: +$by}, time: 1s}]
sequence:
  - move: home
    time: 2s
  - section: nod
    with: {bye: 20}
)");
  EXPECT_EQ(messages(out),
            (std::vector<std::string>{
                "10:12 error: section 'nod' has no parameter 'bye'; did you mean 'by'?",
                "9:14 note: section 'nod' is performed here"}));
}

TEST(UnperformedSections, AreWarnedOnTheCarToo) {
  auto out = compile_text(R"(robot: raspblock
sections:
  spin: [{drive: {z: 100}, time: 1s}]
sequence:
  - drive: {x: 10}
    time: 1s
)");
  EXPECT_TRUE(out.raspblock_program() != nullptr) << diagnostics_of(out);
  EXPECT_EQ(messages(out),
            std::vector<std::string>{"3:3 warning: section 'spin' is defined but never performed"});
}

}  // namespace
}  // namespace seqc::compiler
