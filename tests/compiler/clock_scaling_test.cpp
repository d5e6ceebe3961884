// CompileOptions::clock_ppm: a board whose clock is e fast gets action times pre-scaled by
// (1 + e), every boundary multiplied on the absolute timeline and rounded once, so a long song
// neither drifts nor gains rounding error action by action; eased and `through` curves followed
// within tolerance on the scaled clock (a straight-line model of the board and the curves'
// formulas written here); and --resync's pieces at bar lines (compiler::split_at_bars).
// Boundaries are worked out by hand.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "compiler/targets/servo_controller/resync.hpp"
#include "tests/compiler/lang_test_util.hpp"
#include "tests/six_bars_dance.hpp"

namespace seqc::compiler {
namespace {

using testing::MemoryFiles;
using testing::program_of;

CompileOutput compile_with_clock(const std::string& text, std::int32_t ppm) {
  MemoryFiles files;
  files.files["main.yaml"] = text;
  CompileOptions options;
  options.clock_ppm = ppm;
  return compile_file("main.yaml", files, options);
}

// 240 one-second moves, back and forth.
const char* kSecondMoves = R"(robot: xarm
sequence:
  - repeat: 120
    do:
      - move: {base: 600}
        time: 1s
      - move: {base: 400}
        time: 1s
)";

TEST(ClockScaling, OneSecondActionsOnAFastClockLast1008Ms) {
  const auto out = compile_with_clock(kSecondMoves, 8000);
  const ServoProgram& p = program_of(out);
  ASSERT_EQ(p.keyframes.size(), 240u);
  for (std::size_t k = 0; k < p.keyframes.size(); ++k) {
    SCOPED_TRACE(k);
    // Boundary k at k x 1000 x 1.008 = k x 1008 ms.
    EXPECT_EQ(p.keyframes[k].start_ms, k * 1008);
    EXPECT_EQ(p.keyframes[k].time_ms, 1008);
  }
  EXPECT_EQ(p.keyframes[1].targets, (std::vector<lsc::ServoTarget>{{6, 400}}));
  EXPECT_EQ(p.duration_ms(), 241920u);  // 240 x 1008
}

TEST(ClockScaling, ASlowClockShortensAndNoClockLeavesTimesAlone) {
  const auto slow_out = compile_with_clock(kSecondMoves, -10000);
  const ServoProgram& slow = program_of(slow_out);
  ASSERT_EQ(slow.keyframes.size(), 240u);
  EXPECT_EQ(slow.keyframes[239].start_ms, 239u * 990);  // 1000 x 0.99
  EXPECT_EQ(slow.duration_ms(), 237600u);               // 240 x 990
  const auto exact_out = compile_with_clock(kSecondMoves, 0);
  const ServoProgram& exact = program_of(exact_out);
  EXPECT_EQ(exact.keyframes[239].start_ms, 239000u);
  EXPECT_EQ(exact.duration_ms(), 240000u);
}

TEST(ClockScaling, BoundariesAreRoundedOnceNotActionByAction) {
  // A beat at 110 bpm is 6000/11 ms; on a clock +8000 ppm fast 6048/11 = 549.8181... ms.
  // Boundary k is round(k x 6048 / 11): 550, 1100 (1099.64), 1649 (1649.45), 2199 (2199.27),
  // 2749 (2749.09), ... 6048 at beat 11. Rounding each action (550 ms) would end at 6050.
  const auto out = compile_with_clock(R"(robot: xarm
tempo: 110
sequence:
  - repeat: 11
    do:
      - move: {base: 600}
        time: 1b
      - move: {base: 400}
        time: 1b
)",
                                      8000);
  const ServoProgram& p = program_of(out);
  ASSERT_EQ(p.keyframes.size(), 22u);
  EXPECT_EQ(p.keyframes[1].start_ms, 550u);
  EXPECT_EQ(p.keyframes[2].start_ms, 1100u);
  EXPECT_EQ(p.keyframes[3].start_ms, 1649u);
  EXPECT_EQ(p.keyframes[4].start_ms, 2199u);
  EXPECT_EQ(p.keyframes[5].start_ms, 2749u);
  EXPECT_EQ(p.keyframes[2].time_ms, 549);  // 1649 - 1100
  EXPECT_EQ(p.keyframes[11].start_ms, 6048u);
  EXPECT_EQ(p.duration_ms(), 12096u);  // 22 beats: 2 x 6048
}

TEST(ClockScaling, CurvesStretchWithTheirEnds) {
  // A straight second, then an eased move of 2 s: it ends at 3000 x 1.008 = 3024 ms on a clock
  // +8000 ppm fast, and the servo is where it was meant to be at the end.
  const auto out = compile_with_clock(R"(robot: xarm
sequence:
  - move: {base: 500}
    time: 1s
  - move: {base: 900}
    time: 2s
    ease: in-out
)",
                                      8000);
  const ServoProgram& p = program_of(out);
  ASSERT_FALSE(p.keyframes.empty());
  const Keyframe& last = p.keyframes.back();
  EXPECT_EQ(p.keyframes[0].time_ms, 1008);
  EXPECT_GT(p.keyframes.size(), 2u) << "the curve takes several actions";
  EXPECT_EQ(last.start_ms + last.time_ms, 3024u);
  EXPECT_EQ(last.targets, (std::vector<lsc::ServoTarget>{{6, 900}}));
  // The program's timeline stays the author's (plots and simulate read it in host time).
  EXPECT_EQ(p.timeline.end, ExactMs(3000));
}

// ---- Curves on a scaled clock, checked by a model written here ---------------------------------

// The author's curve for base: 1 s straight to 500 (from an unknown start, not checked), then
// sine-in-out to 900 over 2 s, then `through` 300 (800 ms) and 700 (1200 ms). Author times.
double base_curve(double t) {
  if (t <= 3000) {
    // sine-in-out(u) = -(cos(pi u) - 1) / 2, u over 1000..3000 ms.
    const double u = (t - 1000) / 2000;
    return 500 + 400 * (-(std::cos(std::numbers::pi * u) - 1) / 2);
  }
  // C1 cubic Hermite through (3000, 900), (3800, 300), (5000, 700): slope 0 at both ends, at
  // the interior waypoint (700 - 900) / (5000 - 3000) = -0.1 unit/ms.
  const auto hermite = [](double s, double pa, double ma, double pb, double mb, double h) {
    const double s2 = s * s, s3 = s2 * s;
    return (2 * s3 - 3 * s2 + 1) * pa + (s3 - 2 * s2 + s) * h * ma + (-2 * s3 + 3 * s2) * pb +
           (s3 - s2) * h * mb;
  };
  if (t <= 3800) return hermite((t - 3000) / 800, 900, 0, 300, -0.1, 800);
  return hermite((t - 3800) / 1200, 300, -0.1, 700, 0, 1200);
}

const char* kCurvedBase = R"(robot: xarm
sequence:
  - move: {base: 500}
    time: 1s
  - move: {base: 900}
    time: 2s
    ease: sine-in-out
  - through:
      - pose: {base: 300}
        time: 800ms
      - pose: {base: 700}
        time: 1200ms
)";

// The board moves each servo on a straight line from the previous action's target to this
// one's over the action's time, on its own clock; a clock (1 + e) fast reads b = t (1 + e) when
// the author's curve is at t. At every whole ms b of the board past the first action the line
// must be within the default tolerance (1 unit) of the curve at b / (1 + e).
void expect_curve_followed(std::int32_t ppm, std::uint32_t first_end, std::uint32_t end) {
  SCOPED_TRACE(ppm);
  const auto out = compile_with_clock(kCurvedBase, ppm);
  const ServoProgram& p = program_of(out);
  ASSERT_GT(p.keyframes.size(), 3u);
  EXPECT_EQ(p.keyframes[0].start_ms + p.keyframes[0].time_ms, first_end);
  const Keyframe& last = p.keyframes.back();
  EXPECT_EQ(last.start_ms + last.time_ms, end);
  ASSERT_EQ(last.targets, (std::vector<lsc::ServoTarget>{{6, 700}}));
  const double scale = 1 + ppm / 1e6;
  double worst = 0;
  for (std::size_t k = 1; k < p.keyframes.size(); ++k) {
    const Keyframe& prev = p.keyframes[k - 1];
    const Keyframe& f = p.keyframes[k];
    ASSERT_EQ(prev.start_ms + prev.time_ms, f.start_ms) << k;
    ASSERT_EQ(f.targets.size(), 1u) << k;
    ASSERT_EQ(prev.targets.size(), 1u) << k;
    const double from = prev.targets[0].position;
    const double to = f.targets[0].position;
    for (std::uint32_t b = f.start_ms; b <= f.start_ms + f.time_ms; ++b) {
      const double line = from + (to - from) * (b - f.start_ms) / f.time_ms;
      const double err = std::abs(line - base_curve(b / scale));
      worst = std::max(worst, err);
      EXPECT_LE(err, 1.0 + 1e-9) << "board ms " << b << ": line " << line << ", curve "
                                 << base_curve(b / scale);
    }
  }
  EXPECT_GT(worst, 0.0);
}

TEST(ClockScaling, EasedAndThroughCurvesStayWithinToleranceOnAFastClock) {
  // +20000 ppm: the first move ends at 1000 x 1.02 = 1020, the whole at 5000 x 1.02 = 5100.
  expect_curve_followed(20000, 1020, 5100);
}

TEST(ClockScaling, EasedAndThroughCurvesStayWithinToleranceOnTheFastestClockTaken) {
  // +200000 ppm (20 %, the largest --clock-ppm): 1000 x 1.2 = 1200 and 5000 x 1.2 = 6000. The
  // interior slope of `through` on the board's clock is -0.1 / 1.2 unit/ms; left at -0.1, the
  // curve would be off by up to 1200 x (0.1 - 0.1 / 1.2) x 4/27 = 2.96 units (the Hermite
  // h10 term's largest size, 4/27, at s = 1/3 of the second span).
  expect_curve_followed(200000, 1200, 6000);
}

TEST(ClockScaling, EasedAndThroughCurvesStayWithinToleranceOnASlowClock) {
  // -20000 ppm: 1000 x 0.98 = 980 and 5000 x 0.98 = 4900.
  expect_curve_followed(-20000, 980, 4900);
}

// ---- --resync: pieces at bar lines ------------------------------------------------------------

// 24 one-beat moves at 120 bpm in 4/4: a bar is 2000 ms, the dance 12 s.
constexpr const char* kSixBars = seqc::testing::kSixBarsDance;

TEST(Resync, EveryTwoBarsAPiece) {
  const auto out = compile_with_clock(kSixBars, 0);
  auto pieces = compiler::split_at_bars(program_of(out), 2);
  ASSERT_TRUE(pieces) << pieces.error().message;
  // Bar lines 2 and 4 at 4000 and 8000 ms; bar 6 is the end, so three pieces of 8 actions.
  ASSERT_EQ(pieces->size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) {
    SCOPED_TRACE(k);
    EXPECT_EQ((*pieces)[k].host_start, ExactMs(static_cast<std::int64_t>(k) * 4000));
    EXPECT_EQ((*pieces)[k].board_start_ms, k * 4000);
    ASSERT_EQ((*pieces)[k].keyframes.size(), 8u);
    EXPECT_EQ((*pieces)[k].keyframes[0].start_ms, 0u);
    EXPECT_EQ((*pieces)[k].keyframes[1].start_ms, 500u);
  }
}

TEST(Resync, APreScaledPieceStartsAtItsHostTime) {
  // At +8000 ppm bar 2 falls at 4000 x 1.008 = 4032 ms of the board's clock, which the host
  // reaches at 4032 / 1.008 = 4000 ms.
  const auto out = compile_with_clock(kSixBars, 8000);
  auto pieces = compiler::split_at_bars(program_of(out), 2, 8000);
  ASSERT_TRUE(pieces) << pieces.error().message;
  ASSERT_EQ(pieces->size(), 3u);
  EXPECT_EQ((*pieces)[1].board_start_ms, 4032u);
  EXPECT_EQ((*pieces)[1].host_start, ExactMs(4000));
  EXPECT_EQ((*pieces)[2].board_start_ms, 8064u);
  EXPECT_EQ((*pieces)[2].host_start, ExactMs(8000));
}

TEST(Resync, UnderAClockScaleEveryPieceStartsOnTheScaledBarLine) {
  // +3333 ppm: a 2000 ms bar lasts 2000 x 1.003333 = 2006.666 ms of the board's clock, and a
  // beat boundary k falls at round(k x 501.6665). Bar line k (beat 4k) is at
  //   k=1: 2006.666 -> 2007   k=2: 4013.332 -> 4013   k=3: 6019.998 -> 6020
  //   k=4: 8026.664 -> 8027   k=5: 10033.33 -> 10033
  // each on an action boundary, so piece k starts there; the host starts it at that board time
  // divided by 1.003333: 2007 x 1000000 / 1003333 ms and so on (kept exact).
  const auto out = compile_with_clock(kSixBars, 3333);
  auto pieces = compiler::split_at_bars(program_of(out), 1, 3333);
  ASSERT_TRUE(pieces) << pieces.error().message;
  ASSERT_EQ(pieces->size(), 6u);
  const std::uint32_t board[6] = {0, 2007, 4013, 6020, 8027, 10033};
  for (std::size_t k = 0; k < 6; ++k) {
    SCOPED_TRACE(k);
    EXPECT_EQ((*pieces)[k].board_start_ms, board[k]);
    EXPECT_EQ((*pieces)[k].host_start, ExactMs::ratio(std::int64_t{board[k]} * 1000000, 1003333));
    ASSERT_EQ((*pieces)[k].keyframes.size(), 4u);
    EXPECT_EQ((*pieces)[k].keyframes[0].start_ms, 0u);
  }
  // Inside piece 1 the second action starts at beat 5: round(2508.3325) - 2007 = 501.
  EXPECT_EQ((*pieces)[1].keyframes[1].start_ms, 501u);

  // -20000 ppm, every two bars: 4000 x 0.98 = 3920 and 8000 x 0.98 = 7840 (whole ms); the host
  // reaches them at 3920 / 0.98 = 4000 and 7840 / 0.98 = 8000 ms.
  const auto slow_out = compile_with_clock(kSixBars, -20000);
  auto slow = compiler::split_at_bars(program_of(slow_out), 2, -20000);
  ASSERT_TRUE(slow) << slow.error().message;
  ASSERT_EQ(slow->size(), 3u);
  EXPECT_EQ((*slow)[1].board_start_ms, 3920u);
  EXPECT_EQ((*slow)[1].host_start, ExactMs(4000));
  EXPECT_EQ((*slow)[2].board_start_ms, 7840u);
  EXPECT_EQ((*slow)[2].host_start, ExactMs(8000));
  EXPECT_EQ((*slow)[2].keyframes.size(), 8u);
}

TEST(Resync, APieceStartsAtTheBoundaryNearestItsBarLine) {
  // Three-beat moves (1500 ms) against 2000 ms bars: boundaries at 0, 1500, 3000, 4500. Bar 1
  // (2000 ms) is nearest 1500, bar 2 (4000 ms) nearest 4500; bar 3 is the end (6000 ms).
  const auto out = compile_with_clock(R"(robot: xarm
tempo: 120
meter: 4/4
sequence:
  - repeat: 2
    do:
      - move: {base: 600}
        time: 3b
      - move: {base: 400}
        time: 3b
)",
                                      0);
  auto pieces = compiler::split_at_bars(program_of(out), 1);
  ASSERT_TRUE(pieces) << pieces.error().message;
  ASSERT_EQ(pieces->size(), 3u);
  EXPECT_EQ((*pieces)[0].keyframes.size(), 1u);
  EXPECT_EQ((*pieces)[1].host_start, ExactMs(1500));
  EXPECT_EQ((*pieces)[1].keyframes.size(), 2u);
  EXPECT_EQ((*pieces)[2].host_start, ExactMs(4500));
  EXPECT_EQ((*pieces)[2].keyframes.size(), 1u);
}

TEST(Resync, NeedsBarLines) {
  const auto out = compile_with_clock(kSecondMoves, 0);
  auto pieces = compiler::split_at_bars(program_of(out), 2);
  ASSERT_FALSE(pieces);
  EXPECT_EQ(pieces.error().message,
            "--resync needs bar lines: give the file a tempo and a meter (or a music: block)");
}

}  // namespace
}  // namespace seqc::compiler
