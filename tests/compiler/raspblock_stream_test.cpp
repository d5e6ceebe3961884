// The compiled Raspblock stream, byte for byte. Every expected frame below was written by hand
// from docs/protocol/raspblock.md (FF FE FUNC LEN DATA CHK,
// CHK = FUNC + LEN + sum(DATA), 16-bit values big-endian, rocker signs in 0b00000XYZ with the
// Z bit set for Z >= 0); the arithmetic is in the comments.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "compiler/formats/plot_svg.hpp"
#include "compiler/formats/raspblock_listing.hpp"
#include "compiler/targets/raspblock/raspblock_stream.hpp"
#include "tests/compiler/lang_test_util.hpp"
#include "tests/compiler/raspblock_frames.hpp"

namespace seqc::compiler {
namespace {

using testing::compile_text;
using testing::diagnostics_of;

using testing::frames_of;
using testing::kStop;

TEST(RaspblockStream, DriveThenStop) {
  // The vendor driver's example: X=-10 -> 01 00 0a 00 00 00 00 05; 03+08+01+0a+05 = 1b.
  EXPECT_EQ(
      frames_of("robot: raspblock\n"
                "sequence:\n"
                "  - drive: {x: -10}\n"
                "    time: 500ms\n"),
      (std::vector<std::string>{"0: ff fe 03 08 01 00 0a 00 00 00 00 05 1b", "500: " + kStop}));
}

// A drive followed by a `together` whose track drives at its start: the block itself does not
// drive, so a stop was due at 500 ms, but the track's speeds replace it in the same millisecond.
// The car follows the last speeds it gets, so only the new speeds go out: x=10 (0a; x > 0 sets
// no X bit, z = 0 sets the Z bit) -> signs 01; 03+08+01+0a+01 = 0x17. The gimbal at 1500/1500
// (05 dc 05 dc): 02+04+05+dc+05+dc = 0x1c8 -> c8.
TEST(RaspblockStream, ANewDriveAtTheJoinReplacesTheStopDueThere) {
  EXPECT_EQ(frames_of("robot: raspblock\n"
                      "sequence:\n"
                      "  - drive: {x: -10}\n"
                      "    time: 500ms\n"
                      "  - together:\n"
                      "      wheels:\n"
                      "        - drive: {x: 10}\n"
                      "          time: 500ms\n"
                      "      camera:\n"
                      "        - move: {pan: 1500, tilt: 1500}\n"
                      "          time: 500ms\n"),
            (std::vector<std::string>{"0: ff fe 03 08 01 00 0a 00 00 00 00 05 1b",
                                      "500: ff fe 03 08 01 00 0a 00 00 00 00 01 17",
                                      "500: ff fe 02 04 05 dc 05 dc c8", "1000: " + kStop}));
}

TEST(RaspblockStream, PidGimbalDrivesAndAServo) {
  const std::vector<std::string> want = {
      // PID position mode, gains 10..17: 01+09+01+0a+...+11 = 0x77.
      "0: ff fe 01 09 01 0a 0b 0c 0d 0e 0f 10 11 77",
      // Gimbal 1500 (05 dc), 1000 (03 e8): 02+04+05+dc+03+e8 = 0x1d2 -> d2.
      "0: ff fe 02 04 05 dc 03 e8 d2",
      // pan 1500 -> 1700 over 200ms at 100ms resolution: 1600 at 100ms, 1700 at 200ms.
      "100: ff fe 02 04 06 40 03 e8 37",  // 1600 = 06 40; 02+04+06+40+03+e8 = 0x137
      "200: ff fe 02 04 06 a4 03 e8 9b",  // 1700 = 06 a4; 0x19b
      // y=20, z=-150: magnitudes 0x14, 0x96; no bit for y>0, no Z bit for z<0; sum 0xb6.
      "300: ff fe 03 08 01 00 00 00 14 00 96 00 b6",
      // The next drive replaces the speeds at once (no stop between): x=5, z=30 -> Z bit.
      "1300: ff fe 03 08 01 00 05 00 00 00 1e 01 30",
      // A step that does not drive stops the car first, then servo 3 to 2000 (07 d0): 0xdf.
      "2300: " + kStop,
      "2300: ff fe 02 03 03 07 d0 df",
      // The stream always ends stopped.
      "2400: " + kStop,
  };
  EXPECT_EQ(frames_of("robot: raspblock\n"
                      "resolution: 100ms\n"
                      "pid: {mode: position, speed_kp: 10, speed_ki: 11, position_kp: 12,\n"
                      "      position_ki: 13, position_kd: 14, yaw_kp: 15, yaw_ki: 16, "
                      "yaw_kd: 17}\n"
                      "sequence:\n"
                      "  - move: {pan: 1500, tilt: 1000}\n"
                      "    time: 100ms\n"
                      "  - move: {pan: 1700}\n"
                      "    time: 200ms\n"
                      "  - drive: {y: 20, z: -150}\n"
                      "    time: 1s\n"
                      "  - drive: {x: 5, z: 30}\n"
                      "    time: 1s\n"
                      "  - move: {servo3: 2000}\n"
                      "    time: 100ms\n"),
            want);
}

TEST(RaspblockStream, DegreesRoundToTheNearestMicrosecond) {
  // 5deg = 500 + 5 x 2000/180 = 555.56 us: sent as 556 (02 2c), not cut to 555;
  // 02+03+03+02+2c = 0x36.
  EXPECT_EQ(frames_of("robot: raspblock\n"
                      "sequence:\n"
                      "  - move: {servo3: 5deg}\n"
                      "    time: 100ms\n"),
            (std::vector<std::string>{"0: ff fe 02 03 03 02 2c 36", "100: " + kStop}));
}

TEST(RaspblockStream, RepeatWithBeatsAndAWait) {
  const std::string right = "ff fe 03 08 01 00 19 00 00 00 00 01 26";  // x=25: 03+08+01+19+01
  const std::string left = "ff fe 03 08 01 00 19 00 00 00 00 05 2a";   // x=-25: X|Z bits = 05
  const std::string spin = "ff fe 03 08 01 00 00 00 00 00 c8 01 d5";   // z=200: c8, Z bit
  EXPECT_EQ(
      frames_of("robot: raspblock\n"
                "tempo: 120\n"
                "sequence:\n"
                "  - repeat: 2\n"
                "    do:\n"
                "      - drive: {x: 25}\n"
                "        time: 1b\n"
                "      - drive: {x: -25}\n"
                "        time: 1b\n"
                "  - drive: {z: 200}\n"
                "    time: 0.5s\n"
                "  - wait: 1s\n"),
      (std::vector<std::string>{"0: " + right, "500: " + left, "1000: " + right, "1500: " + left,
                                "2000: " + spin, "2500: " + kStop, "3500: " + kStop}));
}

// A beat at 128 bpm is 60000/128 = 468.75 ms. Each send time is the exact beat rounded once
// (halves away from zero), never a sum of rounded steps: 468.75 -> 469, 937.5 -> 938,
// 1406.25 -> 1406 (not 469 + 938 = 1407), 1875, 2343.75 -> 2344, and the stop at 6 beats,
// 2812.5 -> 2813.
TEST(RaspblockStream, BeatsAtAnyTempoAreRoundedOnlyOnTheAbsoluteTimeline) {
  const std::string right = "ff fe 03 08 01 00 19 00 00 00 00 01 26";  // x=25
  const std::string left = "ff fe 03 08 01 00 19 00 00 00 00 05 2a";   // x=-25
  EXPECT_EQ(
      frames_of("robot: raspblock\n"
                "tempo: 128\n"
                "sequence:\n"
                "  - repeat: 3\n"
                "    do:\n"
                "      - drive: {x: 25}\n"
                "        time: 1b\n"
                "      - drive: {x: -25}\n"
                "        time: 1b\n"),
      (std::vector<std::string>{"0: " + right, "469: " + left, "938: " + right, "1406: " + left,
                                "1875: " + right, "2344: " + left, "2813: " + kStop}));
}

// 440 beats at 110 bpm are 440 x 60000 / 110 = 240,000 ms exactly; a beat is 6000/11 =
// 545.45 ms, so rounding each step would end at 440 x 545 = 239,800 ms.
TEST(RaspblockStream, AFourMinuteDanceEndsOnItsLastBeat) {
  auto out = compile_text(
      "robot: raspblock\n"
      "tempo: 110\n"
      "sequence:\n"
      "  - repeat: 220\n"
      "    do:\n"
      "      - drive: {x: 25}\n"
      "        time: 1b\n"
      "      - drive: {x: -25}\n"
      "        time: 1b\n");
  const RaspblockProgram* p = out.raspblock_program();
  ASSERT_NE(p, nullptr) << diagnostics_of(out);
  EXPECT_EQ(p->duration_ms, 240000u);
  ASSERT_EQ(p->packets.size(), 441u);         // a drive per beat, then the stop
  EXPECT_EQ(p->packets[1].at_ms, 545u);       // 545.45
  EXPECT_EQ(p->packets[6].at_ms, 3273u);      // 6 x 6000/11 = 3272.73
  EXPECT_EQ(p->packets[11].at_ms, 6000u);     // 11 beats = 6 s exactly
  EXPECT_EQ(p->packets[439].at_ms, 239455u);  // 439 x 6000/11 = 239454.55
  EXPECT_EQ(p->packets[440].at_ms, 240000u);  // the stop
}

// A move over a beat at 128 bpm split into 4 packets: they leave at k/4 of 468.75 ms after
// the start at 468.75 ms, each rounded once: 468.75 -> 469, 585.94 -> 586, 703.13 -> 703,
// 820.31 -> 820; servo1 1000 -> 1400 linear puts 1100, 1200, 1300, 1400 in them.
TEST(RaspblockStream, MovePacketsAtFractionalTimesRoundOnce) {
  auto out = compile_text(
      "robot: raspblock\n"
      "tempo: 128\n"
      "sequence:\n"
      "  - move: {servo1: 1000}\n"
      "    time: 1b\n"
      "  - move: {servo1: 1400}\n"
      "    time: 1b\n"
      "    steps: 4\n");
  const RaspblockProgram* p = out.raspblock_program();
  ASSERT_NE(p, nullptr) << diagnostics_of(out);
  std::vector<std::pair<std::uint32_t, int>> got;
  for (const auto& tp : p->packets) {
    if (const auto* s = std::get_if<raspblock::SingleServo>(&tp.packet)) {
      got.emplace_back(tp.at_ms, static_cast<int>(s->position));
    }
  }
  const std::vector<std::pair<std::uint32_t, int>> want = {
      {0, 1000}, {469, 1100}, {586, 1200}, {703, 1300}, {820, 1400}};
  EXPECT_EQ(got, want);
  EXPECT_EQ(p->duration_ms, 938u);  // 937.5 rounds away from zero
}

TEST(RaspblockStream, AMoveWhoseStepIsNotAWholeMsArrivesAtItsWrittenTime) {
  // 1999 ms in 100 steps: a step lasts 19.99 ms. The move starts at 100 ms (after the first
  // move's single packet), so step k (1..100), carrying 1000 + k, is sent at
  // 100 + (k - 1) x 19.99 rounded once:
  //   k=1: 100   k=2: 119.99 -> 120   k=51: 1099.5 -> 1100   k=52: 1119.49 -> 1119
  //   k=100: 100 + 1979.01 = 2079.01 -> 2079, and the step ends at 100 + 1999 = 2099 (the stop).
  // A whole-ms step would land elsewhere: 19 ms puts the last packet at 1981 (the target
  // reached at 2000, 99 ms early); 20 ms at 2080 (ending at 2100).
  auto out = compile_text(
      "robot: raspblock\n"
      "sequence:\n"
      "  - move: {servo1: 1000}\n"
      "    time: 100ms\n"
      "    steps: 1\n"
      "  - move: {servo1: 1100}\n"
      "    time: 1999ms\n"
      "    steps: 100\n");
  const RaspblockProgram* p = out.raspblock_program();
  ASSERT_NE(p, nullptr) << diagnostics_of(out);
  std::vector<std::pair<std::uint32_t, int>> got;
  for (const TimedPacket& t : p->packets) {
    if (const auto* s = std::get_if<raspblock::SingleServo>(&t.packet)) {
      got.emplace_back(t.at_ms, s->position);
    }
  }
  ASSERT_EQ(got.size(), 101u);
  EXPECT_EQ(got[0], (std::pair<std::uint32_t, int>{0, 1000}));
  EXPECT_EQ(got[1], (std::pair<std::uint32_t, int>{100, 1001}));
  EXPECT_EQ(got[2], (std::pair<std::uint32_t, int>{120, 1002}));
  EXPECT_EQ(got[51], (std::pair<std::uint32_t, int>{1100, 1051}));
  EXPECT_EQ(got[52], (std::pair<std::uint32_t, int>{1119, 1052}));
  EXPECT_EQ(got[100], (std::pair<std::uint32_t, int>{2079, 1100}));
  for (int k = 1; k <= 100; ++k) {
    SCOPED_TRACE(k);
    // (k - 1) x 1999 / 100 rounded half up, in whole numbers: ((k - 1) x 1999 + 50) / 100.
    const auto at = static_cast<std::uint32_t>(100 + ((k - 1) * 1999 + 50) / 100);
    EXPECT_EQ(got[static_cast<std::size_t>(k)], (std::pair<std::uint32_t, int>{at, 1000 + k}));
  }
  // The target is first sent by the last packet only, and the stream ends as its step ends.
  EXPECT_EQ(p->duration_ms, 2099u);
  ASSERT_FALSE(p->packets.empty());
  EXPECT_EQ(p->packets.back().at_ms, 2099u);
}

TEST(RaspblockStream, MovesInterpolateAtTheResolutionAndSkipRepeats) {
  auto out = compile_text(
      "robot: raspblock\n"
      "sequence:\n"
      "  - move: {servo1: 1000}\n"
      "    time: 100ms\n"
      "  - move: {servo1: 1100}\n"
      "    time: 100ms\n"  // default 20ms resolution: 5 packets, 20 apart
      "  - move: {servo1: 1100}\n"
      "    time: 1s\n"  // already there: nothing to send
      "  - move: {servo1: 90deg}\n"
      "    time: 40ms\n"
      "    steps: 2\n"
      "    ease: in\n");
  const RaspblockProgram* p = out.raspblock_program();
  ASSERT_NE(p, nullptr) << diagnostics_of(out);
  std::vector<std::pair<std::uint32_t, int>> got;
  for (const TimedPacket& t : p->packets) {
    if (const auto* s = std::get_if<raspblock::SingleServo>(&t.packet)) {
      EXPECT_EQ(s->index, 1);
      got.emplace_back(t.at_ms, s->position);
    }
  }
  // 90deg = 500 + 90 * 2000/180 = 1500; ease in at k=1 of 2: 1100 + 400 * 0.25 = 1200.
  const std::vector<std::pair<std::uint32_t, int>> want = {{0, 1000},    {100, 1020}, {120, 1040},
                                                           {140, 1060},  {160, 1080}, {180, 1100},
                                                           {1200, 1200}, {1220, 1500}};
  EXPECT_EQ(got, want);
  EXPECT_EQ(p->duration_ms, 1240u);
  ASSERT_FALSE(p->packets.empty());
  EXPECT_EQ(p->packets.back().packet, (raspblock::Packet{raspblock::Rocker{0, 0, 0}}));
  EXPECT_EQ(p->packets.back().at_ms, 1240u);
}

TEST(RaspblockStream, GimbalMovesFollowTheSameCurvesAsTheArm) {
  auto out = compile_text(
      "robot: raspblock\n"
      "sequence:\n"
      "  - move: {pan: 1000, tilt: home}\n"
      "    time: 100ms\n"
      "  - move: {pan: 2000}\n"
      "    time: 200ms\n"
      "    ease: sine-in-out\n"
      "    steps: 4\n");
  const RaspblockProgram* p = out.raspblock_program();
  ASSERT_NE(p, nullptr) << diagnostics_of(out);
  // The timeline holds the intended curve: sine-in-out is half way at half time.
  ASSERT_EQ(p->timeline.servo_count(), 6u);
  ASSERT_EQ(p->timeline.count(0), 2u);
  EXPECT_DOUBLE_EQ(*p->timeline.value(0, 200), 1500);
  // The packets sample it: (1 - cos(pi k/4)) / 2 of the way at k = 1..4, sent at (k-1)/4.
  std::vector<std::pair<std::uint32_t, int>> got;
  for (const TimedPacket& t : p->packets) {
    if (const auto* g = std::get_if<raspblock::GimbalServos>(&t.packet)) {
      got.emplace_back(t.at_ms, g->horizontal);
    }
  }
  const std::vector<std::pair<std::uint32_t, int>> want = {
      {0, 1000}, {100, 1146}, {150, 1500}, {200, 1854}, {250, 2000}};
  EXPECT_EQ(got, want);
}

// The car's plot reads like the arm's: values on each lane, seconds on the time axis, and a
// scale on the path. Lanes span 400-2600 us over 70 px from y = 74 (pan), 154 (tilt), 234
// (servo1), so 1500 us sits 35 px up from a lane's bottom: y = 74 + 70 - 35 = 109 for pan
// (its label 3 px lower, at 112), 189 for tilt, 269 for servo1; labels right-aligned at x = 144.
// Driving y = 10 for 2 s goes 20 nominal cm forward: the path panel's 320 px span 20 cm, and
// the scale bar is a quarter of that, 5 cm = 80 px.
TEST(RaspblockPlot, LanesHaveValuesAndThePathHasAScale) {
  auto out = compile_text(
      "robot: raspblock\n"
      "sequence:\n"
      "  - move: {pan: 1500, tilt: 1500, servo1: 900}\n"
      "    time: 100ms\n"
      "  - drive: {y: 10}\n"
      "    time: 2s\n");
  ASSERT_NE(out.raspblock_program(), nullptr) << diagnostics_of(out);
  const std::string svg = compiler::plot_car_program(*out.raspblock_program(), {});
  for (
      const char* label :
      {"<text x=\"144\" y=\"112\" text-anchor=\"end\" fill=\"#9ca3af\" font-size=\"9\">1500</text>",
       "<text x=\"144\" y=\"192\" text-anchor=\"end\" fill=\"#9ca3af\" font-size=\"9\">1500</text>",
       "<text x=\"144\" y=\"272\" text-anchor=\"end\" fill=\"#9ca3af\" font-size=\"9\">1500</text>",
       // 2500 us: 2100 of the lane's 2200 us above its bottom, 66.82 px: y = 77.18, label 80.18.
       "<text x=\"144\" y=\"80.18\" text-anchor=\"end\" fill=\"#9ca3af\" "
       "font-size=\"9\">2500</text>",
       ">500</text>", ">1 s</text>", ">2 s</text>", "<title>scale: 5 cm (nominal)</title>",
       ">5 cm</text>"}) {
    EXPECT_NE(svg.find(label), std::string::npos) << label;
  }
  // The bar itself: from the panel's left edge (x = 150) 80 px long.
  EXPECT_NE(svg.find("x1=\"150\""), std::string::npos);
  EXPECT_NE(svg.find("x2=\"230\""), std::string::npos);
}

TEST(RaspblockStream, HexListsSendTimesRightAligned) {
  auto out = compile_text("robot: raspblock\nsequence:\n  - drive: {x: -10}\n    time: 12.5s\n");
  ASSERT_NE(out.raspblock_program(), nullptr) << diagnostics_of(out);
  auto frames = compiler::plan_stream(*out.raspblock_program());
  ASSERT_TRUE(frames.ok());
  EXPECT_EQ(compiler::render_stream_hex(*frames),
            "     0 ms  ff fe 03 08 01 00 0a 00 00 00 00 05 1b\n"
            " 12500 ms  ff fe 03 08 01 00 00 00 00 00 00 01 0d\n");
  EXPECT_EQ(to_hex(compiler::stop_frame()), kStop);
}

}  // namespace
}  // namespace seqc::compiler
