// `seqc servo read|off|move|mode` end to end against the emulated controller.
#include <gtest/gtest.h>

#include "tests/cli/device_test_util.hpp"

namespace seqc::cli::test {
namespace {

using std::chrono::milliseconds;

TEST(DeviceServo, ReadPrintsATable) {
  DeviceHarness h;
  RunResult r = h.run({"servo", "read", "1", "2", "3", "--port", "emu:xarm"});
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(h.received(), hex("55 55 06 15 03 01 02 03"));
  EXPECT_EQ(r.out,
            "servo  position\n"
            "1      500\n"
            "2      500\n"
            "3      500\n");
}

TEST(DeviceServo, ReadWithAProfileReadsEveryServoByName) {
  DeviceHarness h;
  RunResult r = h.run({"servo", "read", "--robot", "xarm", "--port", "emu:xarm"});
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(h.received(), hex("55 55 09 15 06 01 02 03 04 05 06"));
  EXPECT_EQ(r.out,
            "servo  name         position\n"
            "1      claw         500\n"
            "2      wrist_roll   500\n"
            "3      wrist_pitch  500\n"
            "4      elbow        500\n"
            "5      shoulder     500\n"
            "6      base         500\n");
}

TEST(DeviceServo, ReadReportsServosThatDoNotAnswer) {
  DeviceHarness h;  // six servos on the emulated bus
  RunResult r = h.run({"servo", "read", "2", "9", "--port", "emu:xarm"});
  EXPECT_EQ(r.code, 4);
  EXPECT_EQ(h.received(), hex("55 55 05 15 02 02 09"));
  EXPECT_EQ(r.out,
            "servo  position\n"
            "2      500\n"
            "9      no answer\n");
  EXPECT_EQ(r.err,
            "seqc: error: the controller reported no position for servo 9 (not on the bus, or "
            "not answering)\n");
}

TEST(DeviceServo, ReadNeedsServosOrAProfile) {
  DeviceHarness h;
  RunResult r = h.run({"servo", "read", "--port", "emu:xarm"});
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err,
            "seqc: error: name the servos to read, or give --robot to read all of a profile's\n");
  r = h.run({"servo", "read", "1", "1", "--port", "emu:xarm"});
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err, "seqc: error: servo 1 is named twice\n");
  r = h.run({"servo", "read", "claw", "--port", "emu:xarm"});
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err,
            "seqc: error: servo 'claw' is not an id; servo names need a profile, e.g. --robot "
            "xarm\n");
  EXPECT_EQ(h.received(), "");
}

TEST(DeviceServo, MoveSendsOneMultiServoMove) {
  DeviceHarness h;
  RunResult r = h.run({"servo", "move", "1=500", "2=700", "--time", "1s", "--port", "emu:xarm"});
  EXPECT_EQ(r.code, 0) << r.err;
  // 03 count timeLo timeHi {id posLo posHi}: 1000 ms = e8 03, 700 = bc 02.
  EXPECT_EQ(h.received(), hex("55 55 0b 03 02 e8 03 01 f4 01 02 bc 02  55 55 02 0f"));
  EXPECT_EQ(r.out, "");
  EXPECT_NE(r.err.find("seqc: moving servo 1 to 500, servo 2 to 700 over 1 s\n"), std::string::npos)
      << r.err;
  EXPECT_EQ(h.emu.servo_position(2, h.clock.now() + milliseconds(1000)), 700);
}

TEST(DeviceServo, MoveByNameWithAProfile) {
  DeviceHarness h;
  RunResult r = h.run(
      {"servo", "move", "claw=200", "--robot", "xarm", "--time", "500ms", "--port", "emu:xarm"});
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(h.received(), hex("55 55 08 03 01 f4 01 01 c8 00  55 55 02 0f"));
  EXPECT_EQ(r.out, "");
  EXPECT_NE(r.err.find("seqc: moving servo 1 (claw) to 200 over 0.5 s\n"), std::string::npos)
      << r.err;
}

TEST(DeviceServo, MoveRangeErrorsNameTheFieldAndSendNothing) {
  DeviceHarness h;
  struct Case {
    std::vector<std::string> args;
    std::string err;
  } cases[] = {
      {{"300=5"}, "servo must be 0..255, got 300"},
      {{"7=100", "--robot", "xarm"}, "servo 7 is not a servo of the xarm profile (ids 1..6)"},
      {{"1=500", "--time", "70s"}, "--time (ms) must be 0..65535, got 70000"},
      {{"1=500", "--time", "1.5ms"}, "--time: '1.5ms' is not whole milliseconds"},
      {{"1:500"}, "move target '1:500' must look like SERVO=POSITION, e.g. 1=500 or claw=200"},
      {{"1=5x"}, "position of servo 1: '5x' is not a whole number"},
  };
  for (const Case& c : cases) {
    std::vector<std::string> args{"servo", "move"};
    args.insert(args.end(), c.args.begin(), c.args.end());
    args.insert(args.end(), {"--port", "emu:xarm"});
    RunResult r = h.run(args);
    EXPECT_EQ(r.code, 2) << c.args[0];
    EXPECT_EQ(r.err, "seqc: error: " + c.err + "\n");
  }
  EXPECT_EQ(h.received(), "");
}

// A position outside the servo's range is invalid input (exit 1), and the emulated controller
// receives no byte at all: not the move, not a battery check.
TEST(DeviceServo, MoveOutsideTheRangeSendsNothing) {
  const std::string no_profile = " on a servo controller (give --robot for a profile's own range)";
  struct Case {
    std::vector<std::string> args;
    std::string err;
  } cases[] = {
      // Without --robot: 0..2500, every servo controller profile's range together.
      {{"1=5000"}, "position of servo 1 must be 0..2500" + no_profile + ", got 5000"},
      {{"1=500", "2=2501"}, "position of servo 2 must be 0..2500" + no_profile + ", got 2501"},
      {{"1=-5"}, "position of servo 1 must be 0..2500" + no_profile + ", got -5"},
      {{"1=70000"}, "position of servo 1 must be 0..2500" + no_profile + ", got 70000"},
      {{"1=65280"}, "position of servo 1 must be 0..2500" + no_profile + ", got 65280"},
      // With --robot: the profile's own range.
      {{"1=1200", "--robot", "xarm"}, "position of servo 1 must be 0..1000 on xarm, got 1200"},
      {{"base=1001", "--robot", "xarm"}, "position of servo 6 must be 0..1000 on xarm, got 1001"},
      {{"ch3=400", "--robot", "lsc-16"},
       "position of servo 3 must be 500..2500 on lsc-16, got 400"},
  };
  for (const Case& c : cases) {
    DeviceHarness h;
    std::vector<std::string> args{"servo", "move"};
    args.insert(args.end(), c.args.begin(), c.args.end());
    args.insert(args.end(), {"--port", "emu:xarm"});
    RunResult r = h.run(args);
    EXPECT_EQ(r.code, 1) << c.args[0];
    EXPECT_EQ(r.err, "seqc: error: " + c.err + "; nothing was sent\n");
    EXPECT_EQ(r.out, "");
    EXPECT_TRUE(h.emu.received_bytes().empty()) << c.args[0];
  }
  // The ends of each range are sent.
  DeviceHarness h;
  RunResult r = h.run({"servo", "move", "1=2500", "2=0", "--port", "emu:xarm"});
  EXPECT_EQ(r.code, 0) << r.err;
  // 2500 = c4 09; 1000 ms = e8 03.
  EXPECT_EQ(h.received(), hex("55 55 0b 03 02 e8 03 01 c4 09 02 00 00  55 55 02 0f"));
}

// `seqc move` on the LSC-6 (which confirms nothing) refuses the same way: no Move frame.
TEST(DeviceServo, MoveOutsideTheLsc6RangeSendsNothing) {
  DeviceHarness h;
  RunResult r = h.run({"servo", "move", "1=2600", "--robot", "lsc-6", "--port", "emu:lsc6"});
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_EQ(r.err,
            "seqc: error: position of servo 1 must be 500..2500 on lsc-6, got 2600; nothing was "
            "sent\n");
}

TEST(DeviceServo, OffSendsMultiServoOff) {
  DeviceHarness h;
  RunResult r = h.run({"servo", "off", "1", "2", "--port", "emu:xarm"});
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(h.received(), hex("55 55 05 14 02 01 02  55 55 02 0f"));
  EXPECT_EQ(r.out, "");
  EXPECT_NE(r.err.find("seqc: servo 1, servo 2: off (no torque)\n"), std::string::npos) << r.err;
}

TEST(DeviceServo, ModeSendsServoSpeed) {
  DeviceHarness h;
  RunResult r = h.run({"servo", "mode", "3", "motor", "--time", "500ms", "--port", "emu:xarm"});
  EXPECT_EQ(r.code, 0) << r.err;
  // 1a servo mode msLo msHi
  EXPECT_EQ(h.received(), hex("55 55 06 1a 03 01 f4 01  55 55 02 0f"));
  EXPECT_EQ(r.out, "");
  EXPECT_NE(r.err.find("seqc: servo 3: motor mode, 500 ms\n"), std::string::npos) << r.err;

  h.mark();
  r = h.run(
      {"servo", "mode", "claw", "servo", "--time", "0ms", "--robot", "xarm", "--port", "emu:xarm"});
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(h.received(), hex("55 55 06 1a 01 00 00 00  55 55 02 0f"));
  EXPECT_EQ(r.out, "");
  EXPECT_NE(r.err.find("seqc: servo 1 (claw): servo mode, 0 ms\n"), std::string::npos) << r.err;
}

TEST(DeviceServo, ModeRejectsUnknownModes) {
  DeviceHarness h;
  RunResult r = h.run({"servo", "mode", "3", "wheel", "--time", "1s", "--port", "emu:xarm"});
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(h.received(), "");
}

}  // namespace
}  // namespace seqc::cli::test
