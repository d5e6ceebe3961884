// Mistakes in Raspblock choreographies: every one reported in a single run, with the wording a
// person reads (line:column severity: message).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "compiler/targets/raspblock/raspblock_link.hpp"
#include "tests/compiler/lang_test_util.hpp"

namespace seqc::compiler {
namespace {

using testing::compile_text;
using testing::diagnostics_of;
using testing::MemoryFiles;
using testing::messages;

TEST(RaspblockValidation, RangesKeysAndNamesInOneRun) {
  auto out = compile_text(
      "robot: raspblock\n"  // 1
      "pid: {mode: postion, speed_kp: 256, speed_ki: 1, position_kp: 1, position_ki: 1,\n"
      "      position_kd: 1, yaw_kp: 1, yaw_ki: 1, yaw_kd: 1}\n"
      "sequence:\n"                            // 4
      "  - drive: {x: 30, y: -26, z: -201}\n"  // 5
      "    tme: 1s\n"                          // 6
      "  - move: {pna: 1500, tilt: 2000}\n"    // 7
      "    time: 1s\n"                         // 8
      "  - move: {servo5: 1500}\n"             // 9
      "    time: 1s\n"                         // 10
      "  - wait: 1s\n"                         // 11
      "    drive: {x: 1}\n"                    // 12
      "  - drive: {x: 1}\n"                    // 13
      "  - move: {servo1: +10}\n"              // 14
      "    time: 2b\n");                       // 15
  EXPECT_FALSE(out.program);
  EXPECT_EQ(messages(out),
            (std::vector<std::string>{
                "2:13 error: unknown pid mode 'postion'; did you mean 'position'?",
                "2:32 error: 'speed_kp' must be 0-255, not 256",
                "6:5 error: unknown key 'tme' in a drive step; did you mean 'time'?",
                "7:12 error: unknown output 'pna' in this move; did you mean 'pan'?",
                "7:29 error: 'tilt' would move to 2000, above its max 1950",
                "9:12 error: unknown output 'servo5' in this move; did you mean 'servo1'?",
                "12:5 error: a step does one thing: 'drive' cannot be combined with 'wait'; "
                "make it a separate step",
                "13:5 error: this drive needs a 'time', e.g. 'time: 500ms'",
                "14:20 error: 'servo1' has no known position yet, so the relative move '+10' has "
                "nothing to add to; move it to an absolute position first",
                "15:11 error: '2b' counts beats but no 'tempo' is set; add e.g. 'tempo: 120' at "
                "the top of the file",
            }))
      << diagnostics_of(out);
}

TEST(RaspblockValidation, AnEaseThatOvershootsTheRangeIsAnError) {
  // pan 1500 -> 2450 on back-out peaks 10% past its target: 1500 + 950 x 1.1000 = 2545, past
  // the gimbal's 2500 (see Timeline.ValueRangeFindsAnEaseTrueExtremeBetweenSamples); servo1
  // 1000 -> 2400 on elastic-out rings past 2400 too. Both ends of each are in range.
  auto out = compile_text(
      "robot: raspblock\n"                                 // 1
      "sequence:\n"                                        // 2
      "  - move: {pan: 1500, tilt: 1500, servo1: 1000}\n"  // 3
      "    time: 1s\n"                                     // 4
      "  - move: {pan: 2450}\n"                            // 5
      "    time: 1s\n"                                     // 6
      "    ease: back-out\n"                               // 7
      "  - move: {servo1: 2400}\n"                         // 8
      "    time: 1s\n"                                     // 9
      "    ease: elastic-out\n"                            // 10
      "  - move: {pan: 2300}\n"  // 11: 1500 -> 2300 peaks at 2380, in range
      "    time: 1s\n"
      "    ease: back-out\n");
  EXPECT_FALSE(out.program);
  const auto m = messages(out);
  ASSERT_EQ(m.size(), 2u) << diagnostics_of(out);
  EXPECT_EQ(m[0],
            "5:5 error: 'pan' would overshoot to 2545 on this back-out curve, above its "
            "max 2500");
  EXPECT_EQ(m[1].rfind("8:5 error: 'servo1' would overshoot to ", 0), 0u) << m[1];
  EXPECT_NE(m[1].find(" on this elastic-out curve, above its max 2500"), std::string::npos) << m[1];
}

TEST(RaspblockValidation, DriveRangesAreSigned) {
  auto out = compile_text(
      "robot: raspblock\n"
      "sequence:\n"
      "  - drive: {x: 30, y: -26, z: -201}\n"
      "    time: 1s\n");
  EXPECT_EQ(messages(out), (std::vector<std::string>{
                               "3:16 error: 'x' must be -25 to 25, not 30",
                               "3:23 error: 'y' must be -25 to 25, not -26",
                               "3:31 error: 'z' must be -200 to 200, not -201",
                           }));
  // The edges themselves are accepted.
  auto edges = compile_text(
      "robot: raspblock\n"
      "sequence:\n"
      "  - drive: {x: -25, y: 25, z: -200}\n"
      "    time: 1s\n"
      "  - drive: {z: 200}\n"
      "    time: 1s\n");
  EXPECT_TRUE(edges.raspblock_program()) << diagnostics_of(edges);
}

TEST(RaspblockValidation, PidNeedsEveryValue) {
  auto out = compile_text(
      "robot: raspblock\n"
      "pid: {mode: speed, speed_kp: 1, speed_ki: 2}\n"
      "sequence:\n"
      "  - wait: 1s\n");
  EXPECT_EQ(messages(out),
            (std::vector<std::string>{
                "2:6 error: 'pid' sets every value at once, so it needs all of mode, speed_kp, "
                "speed_ki, position_kp, position_ki, position_kd, yaw_kp, yaw_ki, yaw_kd; "
                "missing: position_kp, position_ki, position_kd, yaw_kp, yaw_ki, yaw_kd"}));
}

TEST(RaspblockValidation, TheGimbalMovesBothServos) {
  auto out = compile_text(
      "robot: raspblock\n"
      "sequence:\n"
      "  - move: {pan: 1800}\n"
      "    time: 1s\n");
  EXPECT_EQ(messages(out),
            (std::vector<std::string>{
                "3:11 error: the gimbal command sets pan and tilt together and 'tilt' has no "
                "position yet; give both in the first gimbal move, e.g. {pan: 1800, tilt: "
                "home}"}));
  auto ok = compile_text(
      "robot: raspblock\n"
      "sequence:\n"
      "  - move: home\n"
      "    time: 1s\n"
      "  - move: {pan: 1800}\n"
      "    time: 1s\n");
  EXPECT_TRUE(ok.raspblock_program()) << diagnostics_of(ok);
}

TEST(RaspblockValidation, FixedOutputsCannotBeRedefined) {
  auto out = compile_text(
      "robot: {profile: raspblock, servos: {arm: 1}}\n"
      "sequence:\n"
      "  - wait: 1s\n");
  EXPECT_EQ(messages(out),
            (std::vector<std::string>{"1:37 error: the raspblock's outputs are fixed (pan, tilt, "
                                      "servo1-servo4); remove 'servos'"}));
}

TEST(RaspblockValidation, UnknownRobotSuggestsRaspblock) {
  auto out = compile_text("robot: raspblok\nsequence:\n  - wait: 1s\n");
  EXPECT_EQ(
      messages(out),
      (std::vector<std::string>{
          "1:8 error: unknown robot 'raspblok'; did you mean 'raspblock'? (robots: xarm, bus, "
          "lsc-16, lsc-32, lsc-6, learm, raspblock)"}));
}

TEST(RaspblockValidation, AStreamBeyondTheLinkIsAnErrorSayingWhereAndHowMuch) {
  // Gimbal (9 bytes) + two servos (8 each) every millisecond: 25 bytes/ms = 25,000 B/s.
  auto out = compile_text(
      "robot: raspblock\n"
      "resolution: 1ms\n"
      "sequence:\n"
      "  - move: {pan: 500, tilt: 500, servo1: 500, servo2: 500}\n"
      "    time: 1s\n"
      "  - move: {pan: 2500, tilt: 1950, servo1: 2500, servo2: 2500}\n"
      "    time: 1s\n");
  EXPECT_EQ(messages(out),
            (std::vector<std::string>{
                "6:5 error: the stream needs 2,500 bytes in the 100ms from 1 s (25,000 B/s), "
                "more than the 115200-baud link carries (11,520 B/s); use a coarser "
                "'resolution' or fewer 'steps'"}));
  // The same move at 5ms: 25 bytes per 5ms = 5,000 B/s fits.
  auto fits = compile_text(
      "robot: raspblock\n"
      "resolution: 5ms\n"
      "sequence:\n"
      "  - move: {pan: 500, tilt: 500, servo1: 500, servo2: 500}\n"
      "    time: 1s\n"
      "  - move: {pan: 2500, tilt: 1950, servo1: 2500, servo2: 2500}\n"
      "    time: 1s\n");
  EXPECT_TRUE(fits.raspblock_program()) << diagnostics_of(fits);
}

TEST(RaspblockValidation, CapacityWindowIsExactAtTheEdge) {
  // 1,152 bytes in a 100ms window is exactly the link; one byte more is not.
  std::vector<TimedPacket> packets;
  const raspblock::Packet single = raspblock::SingleServo{1, 1500};  // 8 bytes
  for (int i = 0; i < 144; ++i)
    packets.push_back({static_cast<std::uint32_t>(i % 100), single, {}});
  EXPECT_TRUE(find_overloads(packets).empty());  // 144 * 8 = 1,152
  packets.push_back({99, raspblock::Rocker{}, Location{0, 9, 1}});
  auto over = find_overloads(packets);
  ASSERT_EQ(over.size(), 1u);
  EXPECT_EQ(over[0].bytes, 1152u + 13u);
  EXPECT_EQ(over[0].from_ms, 0u);
  // Packets 100ms apart never share a window.
  packets.push_back({199, raspblock::Rocker{}, Location{0, 9, 1}});
  EXPECT_EQ(find_overloads(packets).size(), 1u);
}

TEST(RaspblockValidation, IncludesShareTheStreamAndReportTheirSite) {
  MemoryFiles files;
  files.files["main.yaml"] =
      "robot: raspblock\n"
      "sequence:\n"
      "  - include: spin.yaml\n"
      "  - include: spin.yaml\n";
  files.files["spin.yaml"] =
      "robot: raspblock\n"
      "sequence:\n"
      "  - drive: {z: 250}\n"
      "    time: 1s\n";
  auto out = compile_file("main.yaml", files);
  EXPECT_EQ(messages(out), (std::vector<std::string>{
                               // Reported once, like any mistake met twice.
                               "3:16 error: 'z' must be -200 to 200, not 250",
                               "3:14 note: included from here",
                           }));
  files.files["spin.yaml"] = "robot: raspblock\nsequence:\n  - drive: {z: 150}\n    time: 1s\n";
  auto ok = compile_file("main.yaml", files);
  ASSERT_TRUE(ok.raspblock_program()) << diagnostics_of(ok);
  // Two drives back to back, then the final stop.
  EXPECT_EQ(ok.raspblock_program()->packets.size(), 3u);
  EXPECT_EQ(ok.raspblock_program()->duration_ms, 2000u);
}

}  // namespace
}  // namespace seqc::compiler
