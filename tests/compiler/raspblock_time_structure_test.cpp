// Time and structure in Raspblock files: meter and tempo steps through the tempo map, `at:`
// offsets and bar positions, sections with parameters, and `together` tracks, as the compiled
// stream. Every frame below was written by hand from docs/protocol/raspblock.md (FF FE FUNC LEN
// DATA CHK, CHK = FUNC + LEN + sum(DATA), 16-bit values big-endian, rocker signs in 0b00000XYZ
// with the Z bit set for Z >= 0); the times and the arithmetic are in the comments.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "compiler/targets/raspblock/raspblock_stream.hpp"
#include "tests/compiler/lang_test_util.hpp"
#include "tests/compiler/raspblock_frames.hpp"

namespace seqc::compiler {
namespace {

using testing::compile_text;
using testing::diagnostics_of;
using testing::messages;

using testing::frames_of;
using testing::kStop;

TEST(RaspblockTime, MeterChangeAndBarPosition) {
  // At 120 bpm a beat is 500 ms. Bars 1-4 in 4/4: 16 beats = 8 s; bars 5-8 in 3/4: 12 beats =
  // 6 s; bar 9 beat 3 is 2 beats (1 s) further: 15,000 ms.
  // servo1 to 2000 (07 d0): 02+03+01+07+d0 = 0xdd.
  EXPECT_EQ(frames_of("robot: raspblock\n"
                      "tempo: 120\n"
                      "meter: 4/4\n"
                      "sequence:\n"
                      "  - wait: 4bar\n"
                      "  - meter: 3/4\n"
                      "  - move: {servo1: 2000}\n"
                      "    time: 20ms\n"
                      "    at: bar 9 beat 3\n"),
            (std::vector<std::string>{"15000: ff fe 02 03 01 07 d0 dd", "15020: " + kStop}));
}

TEST(RaspblockTime, TheProgramCarriesTheTempoMap) {
  auto out = compile_text(
      "robot: raspblock\n"
      "tempo: 120\n"
      "meter: 4/4\n"
      "sequence:\n"
      "  - wait: 2bar\n"  // 8 beats of 500 ms: 4 s
      "  - tempo: 60\n"
      "  - meter: 3/4\n"
      "  - wait: 1bar\n");  // 3 beats of 1 s
  const RaspblockProgram* p = out.raspblock_program();
  ASSERT_NE(p, nullptr) << diagnostics_of(out);
  const TempoMap& map = p->timeline.tempo_map;
  ASSERT_EQ(map.changes().size(), 2u);
  EXPECT_EQ(map.changes()[0].bpm, 120);
  EXPECT_EQ(map.changes()[0].beats_per_bar, 4);
  EXPECT_EQ(map.changes()[1].at, ExactMs(4000));
  EXPECT_EQ(map.changes()[1].bpm, 60);
  EXPECT_EQ(map.changes()[1].beats_per_bar, 3);
  // Bar 3 starts at 4 s, bar 4 three seconds later.
  EXPECT_EQ(map.bar_at(ExactMs(7000)), ExactMs(3));
  EXPECT_EQ(p->duration_ms, 7000u);
}

TEST(RaspblockTime, TempoStepsChangeLaterBeats) {
  // 2 beats at 120 bpm = 1000 ms, then 2 beats at 60 bpm = 2000 ms.
  // x = 10: 01 00 0a 00 00 00 00 01 (Z bit); 03+08+01+0a+01 = 0x17.
  EXPECT_EQ(
      frames_of("robot: raspblock\n"
                "tempo: 120\n"
                "sequence:\n"
                "  - wait: 2b\n"
                "  - tempo: 60\n"
                "  - drive: {x: 10}\n"
                "    time: 2b\n"),
      (std::vector<std::string>{"1000: ff fe 03 08 01 00 0a 00 00 00 00 01 17", "3000: " + kStop}));
}

TEST(RaspblockTime, AtOffsetsCountFromTheStartOfTheirList) {
  // servo2 (index 02): 1000 = 03 e8 -> 02+03+02+03+e8 = 0xf2; 2000 = 07 d0 -> 0xde;
  // 1500 = 05 dc -> 02+03+02+05+dc = 0xe8.
  EXPECT_EQ(frames_of("robot: raspblock\n"
                      "tempo: 120\n"
                      "meter: 4/4\n"
                      "sequence:\n"
                      "  - move: {servo2: 1000}\n"
                      "    time: 100ms\n"
                      "    steps: 1\n"
                      "  - move: {servo2: 2000}\n"  // 2 beats after the sequence starts: 1000
                      "    time: 100ms\n"
                      "    steps: 1\n"
                      "    at: 2b\n"
                      "  - repeat: 1\n"  // its list starts at 1100
                      "    do:\n"
                      "      - move: {servo2: 1500}\n"  // 1 bar (2000 ms) later: 3100
                      "        time: 100ms\n"
                      "        steps: 1\n"
                      "        at: 1bar\n"),
            (std::vector<std::string>{"0: ff fe 02 03 02 03 e8 f2", "1000: ff fe 02 03 02 07 d0 de",
                                      "3100: ff fe 02 03 02 05 dc e8", "3200: " + kStop}));
}

TEST(RaspblockTime, AGapBeforeAtStopsTheDriveWhenItsStepEnds) {
  // The drive lasts its beat (500 ms); the move starts at 2 beats (1000 ms).
  // servo1 2000: 0xdd (as above).
  EXPECT_EQ(frames_of("robot: raspblock\n"
                      "tempo: 120\n"
                      "sequence:\n"
                      "  - drive: {x: 10}\n"
                      "    time: 1b\n"
                      "  - move: {servo1: 2000}\n"
                      "    time: 100ms\n"
                      "    steps: 1\n"
                      "    at: 2b\n"),
            (std::vector<std::string>{"0: ff fe 03 08 01 00 0a 00 00 00 00 01 17", "500: " + kStop,
                                      "1000: ff fe 02 03 01 07 d0 dd", "1100: " + kStop}));
}

TEST(RaspblockTime, TogetherRunsTheDriveAndTheGimbalSideBySide) {
  // y = 10: 01 00 00 00 0a 00 00 01; 03+08+01+0a+01 = 0x17, sent at 0.
  // The gimbal track waits 250 ms, then pan 2000 (07 d0), tilt 1000 (03 e8):
  // 02+04+07+d0+03+e8 = 0x1c8 -> c8. The drive's beat ends at 500 ms, where the block (and the
  // sequence) ends: one stop.
  EXPECT_EQ(frames_of("robot: raspblock\n"
                      "tempo: 120\n"
                      "sequence:\n"
                      "  - together:\n"
                      "      wheels:\n"
                      "        - drive: {y: 10}\n"
                      "          time: 1b\n"
                      "      camera:\n"
                      "        - wait: 250ms\n"
                      "        - move: {pan: 2000, tilt: 1000}\n"
                      "          time: 100ms\n"
                      "          steps: 1\n"),
            (std::vector<std::string>{"0: ff fe 03 08 01 00 00 00 0a 00 00 01 17",
                                      "250: ff fe 02 04 07 d0 03 e8 c8", "500: " + kStop}));
}

TEST(RaspblockTime, ADriveTrackShorterThanTheBlockStopsAtItsEnd) {
  // The drive (x = 10, 0x17) lasts 200 ms; the servo track runs until 400 ms.
  // servo4 (index 04) 2000: 02+03+04+07+d0 = 0xe0 at 0, then 1000 (03 e8): 02+03+04+03+e8 = 0xf4
  // at 300.
  EXPECT_EQ(frames_of("robot: raspblock\n"
                      "sequence:\n"
                      "  - together:\n"
                      "      arm:\n"
                      "        - move: {servo4: 2000}\n"
                      "          time: 300ms\n"
                      "          steps: 1\n"
                      "        - move: {servo4: 1000}\n"
                      "          time: 100ms\n"
                      "          steps: 1\n"
                      "      wheels:\n"
                      "        - drive: {x: 10}\n"
                      "          time: 200ms\n"),
            (std::vector<std::string>{"0: ff fe 02 03 04 07 d0 e0",
                                      "0: ff fe 03 08 01 00 0a 00 00 00 00 01 17", "200: " + kStop,
                                      "300: ff fe 02 03 04 03 e8 f4", "400: " + kStop}));
}

TEST(RaspblockTime, ASectionWithParametersPerformedTwice) {
  // pan 1000 (03 e8), tilt 1500 (05 dc): 02+04+03+e8+05+dc = 0x1d2 -> d2;
  // pan 2500 (09 c4), tilt 1500: 02+04+09+c4+05+dc = 0x1b4 -> b4.
  EXPECT_EQ(frames_of("robot: raspblock\n"
                      "sections:\n"
                      "  look:\n"
                      "    params: {to: 2000}\n"
                      "    steps:\n"
                      "      - move: {pan: $to, tilt: 1500}\n"
                      "        time: 100ms\n"
                      "        steps: 1\n"
                      "sequence:\n"
                      "  - section: look\n"
                      "    with: {to: 1000}\n"
                      "  - section: look\n"
                      "    with: {to: 2500}\n"),
            (std::vector<std::string>{"0: ff fe 02 04 03 e8 05 dc d2",
                                      "100: ff fe 02 04 09 c4 05 dc b4", "200: " + kStop}));
}

TEST(RaspblockTime, EveryEasingFamilyShapesAMove) {
  // back-out is 1 - f(1 - t) with f(t) = 2.70158 t^3 - 1.70158 t^2: at t = 1/2,
  // 1 - (0.3376975 - 0.425395) = 1.0876975, so 1000 -> 2000 is at 2087.6975 -> 2088 (08 28)
  // halfway: the first of two packets carries it and is sent as the move starts (100 ms).
  // servo1: 1000 (03 e8) 02+03+01+03+e8 = 0xf1; 2088: 02+03+01+08+28 = 0x36; 2000: 0xdd.
  EXPECT_EQ(frames_of("robot: raspblock\n"
                      "sequence:\n"
                      "  - move: {servo1: 1000}\n"
                      "    time: 100ms\n"
                      "    steps: 1\n"
                      "  - move: {servo1: 2000}\n"
                      "    time: 200ms\n"
                      "    steps: 2\n"
                      "    ease: back-out\n"),
            (std::vector<std::string>{"0: ff fe 02 03 01 03 e8 f1", "100: ff fe 02 03 01 08 28 36",
                                      "200: ff fe 02 03 01 07 d0 dd", "300: " + kStop}));
}

TEST(RaspblockTime, AnOutputInTwoTracksAtAnyDepth) {
  auto out = compile_text(
      "robot: raspblock\n"
      "sequence:\n"
      "  - together:\n"
      "      a:\n"
      "        - move: {servo1: 2000}\n"
      "          time: 100ms\n"
      "      b:\n"
      "        - together:\n"
      "            c:\n"
      "              - move: {servo1: 1000}\n"
      "                time: 100ms\n"
      "            d:\n"
      "              - drive: {x: 1}\n"
      "                time: 100ms\n"
      "              - move: {tilt: 1000, pan: 1000}\n"
      "                time: 100ms\n"
      "      e:\n"
      "        - move: {pan: 2000}\n"
      "          time: 100ms\n"
      "        - drive: {y: 1}\n"
      "          time: 100ms\n");
  EXPECT_EQ(messages(out),
            (std::vector<std::string>{
                "10:17 error: 'servo1' moves in two tracks, 'a' and 'b'; an output may move in one "
                "track of a 'together' only",
                "5:11 note: 'servo1' moves in track 'a' here",
                "18:11 error: 'pan' moves in two tracks, 'b' and 'e'; an output may move in one "
                "track of a 'together' only",
                "15:17 note: 'pan' moves in track 'b' here",
                "20:11 error: the car drives in two tracks, 'b' and 'e'; the drive belongs to one "
                "track of a 'together' only",
                "13:17 note: the car drives in track 'b' here"}));
}

// Pan in one track and tilt in another: one gimbal packet an instant carries both, each axis
// at its value then. Gimbal packet: FF FE 02 04 PAN(2) TILT(2) CHK, CHK = 02 + 04 + the data.
TEST(RaspblockTime, PanAndTiltInSeparateTracksShareEachPacket) {
  // From 100 ms tilt goes 1500 -> 1000 in two steps (1250 at 100 ms, 1000 at 150 ms); from
  // 150 ms pan goes 1500 -> 2000 in two (1750 at 150 ms, 2000 at 200 ms).
  //   0 ms: 1500 1500 = 05 dc 05 dc: 6 + 05 + dc + 05 + dc = 0x1c8 -> c8
  // 100 ms: 1500 1250 = 05 dc 04 e2: 6 + 05 + dc + 04 + e2 = 0x1cd -> cd
  // 150 ms: 1750 1000 = 06 d6 03 e8: 6 + 06 + d6 + 03 + e8 = 0x1cd -> cd (one packet for both)
  // 200 ms: 2000 1000 = 07 d0 03 e8: 6 + 07 + d0 + 03 + e8 = 0x1c8 -> c8
  EXPECT_EQ(
      frames_of("robot: raspblock\n"
                "sequence:\n"
                "  - move: home\n"
                "    time: 100ms\n"
                "  - together:\n"
                "      p:\n"
                "        - wait: 50ms\n"
                "        - move: {pan: 2000}\n"
                "          time: 100ms\n"
                "          steps: 2\n"
                "      t:\n"
                "        - move: {tilt: 1000}\n"
                "          time: 100ms\n"
                "          steps: 2\n"),
      (std::vector<std::string>{"0: ff fe 02 04 05 dc 05 dc c8", "100: ff fe 02 04 05 dc 04 e2 cd",
                                "150: ff fe 02 04 06 d6 03 e8 cd",
                                "200: ff fe 02 04 07 d0 03 e8 c8", "250: " + kStop}));
}

TEST(RaspblockTime, PanAndTiltFirstSetInSeparateTracksAtOneInstant) {
  // Both unknown before: each goes straight to its target in the block's first packet.
  // 2000 1000 = 07 d0 03 e8: 6 + 07 + d0 + 03 + e8 = 0x1c8 -> c8.
  EXPECT_EQ(frames_of("robot: raspblock\n"
                      "sequence:\n"
                      "  - together:\n"
                      "      p:\n"
                      "        - move: {pan: 2000}\n"
                      "          time: 100ms\n"
                      "      t:\n"
                      "        - move: {tilt: 1000}\n"
                      "          time: 100ms\n"),
            (std::vector<std::string>{"0: ff fe 02 04 07 d0 03 e8 c8", "100: " + kStop}));
  // Tilt comes 50 ms later: the packet at 0 ms has no tilt to carry.
  auto out = compile_text(
      "robot: raspblock\n"
      "sequence:\n"
      "  - together:\n"
      "      p:\n"
      "        - move: {pan: 2000}\n"
      "          time: 100ms\n"
      "      t:\n"
      "        - wait: 50ms\n"
      "        - move: {tilt: 1000}\n"
      "          time: 100ms\n");
  EXPECT_EQ(messages(out), (std::vector<std::string>{
                               "5:11 error: the gimbal command sets pan and tilt together and "
                               "'tilt' has no position yet at 0 s; give it one before this, or "
                               "move it at the same instant"}));
}

TEST(RaspblockTime, TempoAndMeterStayOutOfTracks) {
  auto out = compile_text(
      "robot: raspblock\n"
      "tempo: 120\n"
      "meter: 4/4\n"
      "sequence:\n"
      "  - together:\n"
      "      a:\n"
      "        - meter: 3/4\n");
  EXPECT_EQ(messages(out),
            (std::vector<std::string>{
                "7:18 error: 'meter' inside a 'together' track would change the other tracks' "
                "bars too; move it out of the 'together', before or after it",
                "6:7 note: in track 'a' of this 'together'"}));
}

}  // namespace
}  // namespace seqc::compiler
