// A dance longer than one group (compiler/targets/servo_controller/chain.hpp and
// CompileOptions::chain): cut into the fewest groups, each ending on the last bar line it can
// hold, an action running across that bar line cut in two there; the budget of every group the
// board stores; and the error that names the action, the bar, the time and the passes when even
// they cannot hold the dance. Every count, time and position is worked out by hand beside it.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>

#include "compiler/targets/servo_controller/chain.hpp"
#include "tests/compiler/lang_test_util.hpp"

namespace seqc::compiler {
namespace {

using testing::MemoryFiles;

CompileOutput compile_chained(const std::string& text, std::uint8_t first_group = 0,
                              std::int32_t clock_ppm = 0) {
  MemoryFiles files;
  files.files["main.yaml"] = text;
  CompileOptions options;
  options.chain = true;
  options.first_group = first_group;
  options.clock_ppm = clock_ppm;
  return compile_file("main.yaml", files, options);
}

// `moves` straight one-step moves of `beats` beats at 120 bpm in 4/4, base 300, 700, 300, ...:
// each is exactly one action (a straight line), so action k starts at k x beats x 500 ms.
std::string back_and_forth(int pairs, const std::string& beats) {
  return "robot: xarm\ntempo: 120\nmeter: 4/4\nsequence:\n  - repeat: " + std::to_string(pairs) +
         "\n    do:\n      - move: {base: 300}\n        time: " + beats +
         "\n      - move: {base: 700}\n        time: " + beats + "\n";
}

TEST(Chain, ThreeThousandOneBeatMovesTakeThreeGroupsCutOnBarLines) {
  // 3,000 one-beat moves: 4 actions a bar, 750 bars. A group holds 1,020 actions = 255 bars, so
  // group 1 ends on bar line 256 (255 x 2 s = 510 s), group 2 on bar 511 (1,020 s), and group 3
  // holds the 240 bars left (960 actions). Every cut is on an action's start: none is split.
  const CompileOutput out = compile_chained(back_and_forth(1500, "1b"));
  const ServoProgram& p = testing::program_of(out);
  ASSERT_EQ(p.keyframes.size(), 3000u);
  EXPECT_EQ(p.group_capacity, 1020u);
  EXPECT_EQ(p.groups, 255u);
  EXPECT_EQ(p.group_bars, (std::vector<std::int64_t>{1, 256, 511}));
  auto cut = chain_groups(p, p.group_capacity);
  ASSERT_TRUE(cut) << cut.error().message;
  ASSERT_EQ(cut->pieces.size(), 3u);
  EXPECT_EQ(cut->split_actions, 0u);
  const std::size_t sizes[3] = {1020, 1020, 960};
  const std::uint32_t board[3] = {0, 510000, 1020000};
  for (std::size_t k = 0; k < 3; ++k) {
    SCOPED_TRACE(k);
    const ResyncPiece& piece = cut->pieces[k];
    EXPECT_EQ(piece.keyframes.size(), sizes[k]);
    EXPECT_EQ(piece.board_start_ms, board[k]);
    EXPECT_EQ(piece.host_start, ExactMs(std::int64_t{board[k]}));
    // Rebased: the piece's actions start at 0, 500, 1000 ... of its own clock.
    EXPECT_EQ(piece.keyframes[0].start_ms, 0u);
    EXPECT_EQ(piece.keyframes[1].start_ms, 500u);
    // Each group starts on an even action (0, 1,020, 2,040): a pair's first move, base to 300.
    ASSERT_EQ(piece.keyframes[0].targets.size(), 1u);
    EXPECT_EQ(piece.keyframes[0].targets[0].position, 300u);
  }
}

TEST(Chain, OnAFastBoardClockEachGroupStartsOnItsBarLineOfTheHost) {
  // At +8,000 ppm the board's bar line 256 falls at 510,000 x 1.008 = 514,080 ms of its clock,
  // bar 511 at 1,028,160 ms; the host starts them at 510 s and 1,020 s, the bar lines themselves.
  const CompileOutput out = compile_chained(back_and_forth(1500, "1b"), 0, 8000);
  const ServoProgram& p = testing::program_of(out);
  auto cut = chain_groups(p, p.group_capacity, 8000);
  ASSERT_TRUE(cut) << cut.error().message;
  ASSERT_EQ(cut->pieces.size(), 3u);
  EXPECT_EQ(cut->pieces[1].board_start_ms, 514080u);
  EXPECT_EQ(cut->pieces[1].host_start, ExactMs(510000));
  EXPECT_EQ(cut->pieces[2].board_start_ms, 1028160u);
  EXPECT_EQ(cut->pieces[2].host_start, ExactMs(1020000));
}

TEST(Chain, AnActionAcrossTheBarLineIsCutInTwoThere) {
  // Three-beat moves (1.5 s) in 4/4 (2 s bars): actions start at k x 1500 ms, and a bar line
  // falls on one only every 3 bars (6 s). With groups of 10 actions: bar line 8 (14 s) falls in
  // action 9 (13.5-15 s, base 300 -> 700, the action that ends at index 10's start); before it
  // are actions 0-8 and the action's first half, 10 actions; bar 9 (16 s, in action 10) would
  // need 11. So group 1 ends at 14 s with action 9 cut after 500 of its 1,500 ms: base is then a
  // third of the way, 300 + 400 / 3 = 433.33, sent as 433 (0.33 off the line, within 1). Group 2
  // starts on bar 8 with the rest: 1,000 ms to 700.
  const CompileOutput out = compile_chained(back_and_forth(20, "3b"));
  const ServoProgram& p = testing::program_of(out);
  ASSERT_EQ(p.keyframes.size(), 40u);
  auto cut = chain_groups(p, 10);
  ASSERT_TRUE(cut) << cut.error().message;
  ASSERT_GE(cut->pieces.size(), 2u);
  const ResyncPiece& first = cut->pieces[0];
  ASSERT_EQ(first.keyframes.size(), 10u);
  EXPECT_EQ(first.keyframes[9].start_ms, 13500u);
  EXPECT_EQ(first.keyframes[9].time_ms, 500u);
  ASSERT_EQ(first.keyframes[9].targets.size(), 1u);
  EXPECT_EQ(first.keyframes[9].targets[0].position, 433u);
  const ResyncPiece& second = cut->pieces[1];
  EXPECT_EQ(second.board_start_ms, 14000u);
  EXPECT_EQ(second.host_start, ExactMs(14000));
  EXPECT_EQ(cut->bars[1], 8);
  EXPECT_EQ(second.keyframes[0].start_ms, 0u);
  EXPECT_EQ(second.keyframes[0].time_ms, 1000u);
  EXPECT_EQ(second.keyframes[0].targets[0].position, 700u);
  // Group 2 holds the second half and actions 10-18 (to 27 s), then 28 s (bar 15, in action 18,
  // 27-28.5 s) needs 1 + 19 - 10 = 10: cut there, 1,000 ms into 1,500 (base 700 -> 300: 433.33
  // again, 433).
  ASSERT_GE(cut->pieces.size(), 3u);
  EXPECT_EQ(cut->pieces[2].board_start_ms, 28000u);
  EXPECT_EQ(cut->bars[2], 15);
  const Keyframe& last = cut->pieces[1].keyframes.back();
  EXPECT_EQ(last.time_ms, 1000u);
  EXPECT_EQ(last.targets[0].position, 433u);
  // Every group within 10, and every millisecond of the dance in exactly one of them.
  std::uint64_t total = 0;
  for (const ResyncPiece& piece : cut->pieces) {
    EXPECT_LE(piece.keyframes.size(), 10u);
    for (const Keyframe& k : piece.keyframes) total += k.time_ms;
  }
  EXPECT_EQ(total, 40u * 1500u);
}

TEST(Chain, AFirstMoveIsNeverCut) {
  // The first move (6 s, from a position nobody knows) runs across bar lines 2 and 3 (2 s,
  // 4 s): the board can only be told where it ends, so it is never cut.
  const std::string text =
      "robot: xarm\ntempo: 120\nmeter: 4/4\nsequence:\n  - move: {base: 300}\n    time: 3bar\n"
      "  - move: {base: 700}\n    time: 1bar\n  - move: {base: 300}\n    time: 1bar\n";
  const CompileOutput out = compile_chained(text);
  const ServoProgram& p = testing::program_of(out);
  ASSERT_EQ(p.keyframes.size(), 3u);
  auto cut = chain_groups(p, 1);
  ASSERT_TRUE(cut) << cut.error().message;
  // One action a group: bar lines 2 and 3 (2 s, 4 s) are inside the first move and cannot cut
  // it; bar line 4 (6 s) ends it.
  ASSERT_EQ(cut->pieces.size(), 3u);
  EXPECT_EQ(cut->pieces[1].board_start_ms, 6000u);
  EXPECT_EQ(cut->bars[1], 4);
  EXPECT_EQ(cut->pieces[2].board_start_ms, 8000u);
  EXPECT_EQ(cut->split_actions, 0u);
}

TEST(Chain, WithoutBarLinesTheGroupsEndOnActions) {
  // No tempo: 30 moves of 500 ms, groups of 10: cut at 5 s and 10 s, on the actions' starts.
  const std::string text =
      "robot: xarm\nsequence:\n  - repeat: 15\n    do:\n      - move: {base: 300}\n"
      "        time: 500ms\n      - move: {base: 700}\n        time: 500ms\n";
  const CompileOutput out = compile_chained(text);
  const ServoProgram& p = testing::program_of(out);
  auto cut = chain_groups(p, 10);
  ASSERT_TRUE(cut) << cut.error().message;
  ASSERT_EQ(cut->pieces.size(), 3u);
  EXPECT_EQ(cut->pieces[1].board_start_ms, 5000u);
  EXPECT_EQ(cut->pieces[2].board_start_ms, 10000u);
  EXPECT_EQ(cut->bars, (std::vector<std::int64_t>{0, 0, 0}));
}

TEST(Chain, OneGroupWithoutChainAsBefore) {
  // 1,021 one-beat moves in one group: the classic error, with where action 1,021 starts
  // (1,020 beats x 0.5 s = 510 s, beat 1,020 = bar 256 beat 1).
  const CompileOutput out =
      testing::compile_text(back_and_forth(510, "1b") + "  - move: {base: 300}\n    time: 1b\n");
  EXPECT_NE(
      testing::diagnostics_of(out).find(
          "error: the sequence needs at least 1021/1020 actions; a group holds at most 1,020 (4 "
          "blocks of 255), and this step makes action 1,021 at 510 s (bar 256 beat 1)"),
      std::string::npos)
      << testing::diagnostics_of(out);
}

TEST(Chain, BeyondEveryGroupTheErrorNamesTheActionBarTimeAndPass) {
  // From group 250 the dance may take groups 250-254: 5 x 1,020 = 5,100 actions. 3,000 passes
  // of two one-beat moves: action 5,101 is the second move of pass 2,550 (5,101 = 2 x 2,550 + 1
  // counting the first), which starts after 5,100 beats = 2,550 s, on bar 1,276 beat 1. The walk
  // stops there (the lower bound passes the budget), naming the pass; the passes left are
  // counted, not walked: at least 1 + 3,000 x 2 = 6,001 actions.
  const std::string text =
      "robot: xarm\ntempo: 120\nmeter: 4/4\nsequence:\n  - move: {base: 500}\n    time: 1b\n"
      "  - repeat: 3000\n    do:\n      - move: {base: 300}\n        time: 1b\n"
      "      - move: {base: 700}\n        time: 1b\n";
  const CompileOutput out = compile_chained(text, 250);
  const std::string d = testing::diagnostics_of(out);
  EXPECT_FALSE(out.program.has_value());
  EXPECT_NE(d.find("main.yaml:11:9: error: the sequence needs at least 6,001 actions; the 5 "
                   "groups it may take hold 5,100 (1,020 each), and this step makes action 5,101 "
                   "at 2550 s (bar 1276 beat 1)"),
            std::string::npos)
      << d;
  EXPECT_NE(d.find("main.yaml:7:5: note: in pass 2550 of 3000 of this repeat"), std::string::npos)
      << d;
}

TEST(Chain, TheFittedCountBeyondEveryGroupNamesTheBarAndTime) {
  // Eased swings need several actions each: from group 253 (2 groups, 2,040 actions) a long
  // enough dance passes the budget once fitted, not while walked (one action a step is far
  // below it). The error names where the first action that does not fit starts.
  const std::string text =
      "robot: xarm\ntempo: 120\nmeter: 4/4\nsequence:\n  - move: {base: 500}\n    time: 1b\n"
      "  - repeat: 400\n    do:\n"
      "      - move: {base: 300}\n        time: 1b\n        ease: sine-in-out\n"
      "      - move: {base: 700}\n        time: 1b\n        ease: sine-in-out\n";
  const CompileOutput out = compile_chained(text, 253);
  const std::string d = testing::diagnostics_of(out);
  EXPECT_FALSE(out.program.has_value());
  EXPECT_NE(d.find("groups it may take hold 2,040 (1,020 each), and this step makes action "
                   "2,041 at "),
            std::string::npos)
      << d;
  EXPECT_NE(d.find(" (bar "), std::string::npos) << d;
}

TEST(Chain, AnActionFoundTooManyOnceFittedNamesItsPassAndPerformance) {
  // Eased swings are fitted into several actions each, so the walk's lower bound (one a step)
  // stays within the group and the fitted count passes it. However many actions a swing takes,
  // the error's time T must be a swing's start: pass p of the repeat starts at 2 + (p - 1) s
  // (after the 2 s `home`, each pass two beats of 0.5 s), its second move half a second later,
  // and the bar is T / 2 s + 1. The notes name that pass and the section's performance.
  const std::string text =
      "robot: xarm\ntempo: 120\nmeter: 4/4\nsections:\n  swing:\n"
      "    - move: {base: 300, shoulder: 400}\n      time: 1b\n      ease: sine-in-out\n"
      "    - move: {base: 700, shoulder: 600}\n      time: 1b\n      ease: sine-in-out\n"
      "sequence:\n  - move: home\n    time: 1bar\n  - repeat: 200\n    do:\n"
      "      - section: swing\n";
  const CompileOutput out = testing::compile_text(text);
  const std::string d = testing::diagnostics_of(out);
  const std::size_t at = d.find("and this step makes action 1,021 at ");
  ASSERT_NE(at, std::string::npos) << d;
  const double t = std::stod(d.substr(at + 36));
  const double into_passes = t - 2.0;
  ASSERT_GE(into_passes, 0.0) << d;
  const int pass = static_cast<int>(into_passes) + 1;
  const bool second = into_passes - (pass - 1) >= 0.5;
  const int bar = static_cast<int>(t / 2.0) + 1;
  EXPECT_NE(d.find("(bar " + std::to_string(bar) + " beat "), std::string::npos) << d;
  EXPECT_NE(d.find(std::string("main.yaml:") + (second ? "9" : "6") + ":7: error"),
            std::string::npos)
      << d;
  EXPECT_NE(d.find("main.yaml:17:18: note: in section 'swing', performed here"), std::string::npos)
      << d;
  EXPECT_NE(
      d.find("main.yaml:15:5: note: in pass " + std::to_string(pass) + " of 200 of this repeat"),
      std::string::npos)
      << d;
  // The section's note comes before the pass's: innermost first.
  EXPECT_LT(d.find("in section 'swing'"), d.find("in pass "));
}

}  // namespace
}  // namespace seqc::compiler
