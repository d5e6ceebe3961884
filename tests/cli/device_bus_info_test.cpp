// `seqc bus-info read|write` end to end against the emulated controller, including the refusal
// to write without the one-servo confirmation.
#include <gtest/gtest.h>

#include "tests/cli/device_test_util.hpp"

namespace seqc::cli::test {
namespace {

TEST(DeviceBusInfo, ReadPrintsLimitsAndState) {
  DeviceHarness h;
  RunResult r = h.run({"bus-info", "read", "--port", "emu:xarm"});
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(h.received(), hex("55 55 02 1c"));
  EXPECT_EQ(r.out,
            "field           value\n"
            "id              1\n"
            "position-min    0\n"
            "position-max    1000\n"
            "millivolts-min  0\n"
            "millivolts-max  0\n"
            "temp-max        0\n"
            "led             on\n"
            "led-warning     none\n"
            "\n"
            "state       value\n"
            "offset      0\n"
            "position    500\n"
            "temp        32\n"
            "millivolts  7500\n");
}

TEST(DeviceBusInfo, WriteIsRefusedWithoutTheConfirmation) {
  DeviceHarness h;
  RunResult r = h.run({"bus-info", "write", "--position-max", "900", "--port", "emu:xarm"});
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(r.err,
            "seqc: error: bus-info write is not addressed to one servo: every servo on the bus "
            "takes these settings at once. Disconnect all servos but the one to configure, then "
            "add --i-have-one-servo-attached\n");
  EXPECT_EQ(h.received(), "");
}

TEST(DeviceBusInfo, WriteWithEveryFieldSendsOneFrame) {
  DeviceHarness h;
  RunResult r = h.run({"bus-info",
                       "write",
                       "--servo",
                       "1",
                       "--position-min",
                       "100",
                       "--position-max",
                       "900",
                       "--millivolts-min",
                       "6000",
                       "--millivolts-max",
                       "8400",
                       "--temp-max",
                       "85",
                       "--led",
                       "on",
                       "--led-warning",
                       "overheat,overposition",
                       "--i-have-one-servo-attached",
                       "--port",
                       "emu:xarm"});
  EXPECT_EQ(r.code, 0) << r.err;
  // 1b id pminLo pminHi pmaxLo pmaxHi mvminLo mvminHi mvmaxLo mvmaxHi tLo tHi led warn
  EXPECT_EQ(h.received(), hex("55 55 0f 1b 01 64 00 84 03 70 17 d0 20 55 00 00 05  55 55 02 0f"));
  EXPECT_EQ(r.err, "seqc: written to every servo on the bus (kept over power-off):\n");
  EXPECT_EQ(r.out,
            "field           value\n"
            "id              1\n"
            "position-min    100\n"
            "position-max    900\n"
            "millivolts-min  6000\n"
            "millivolts-max  8400\n"
            "temp-max        85\n"
            "led             on\n"
            "led-warning     overheat,overposition\n");
  // The emulated servos now stop at the new limits.
  ASSERT_EQ(h.run({"servo", "move", "3=950", "--time", "20ms", "--port", "emu:xarm"}).code, 0);
  EXPECT_EQ(h.emu.servo_position(3, h.clock.now() + std::chrono::seconds(1)), 900);
}

TEST(DeviceBusInfo, WriteOfSomeFieldsKeepsTheOthers) {
  DeviceHarness h;
  RunResult r = h.run({"bus-info", "write", "--position-max", "900", "--led", "off",
                       "--i-have-one-servo-attached", "--port", "emu:xarm"});
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(h.received(),
            hex("55 55 02 1c  55 55 0f 1b 01 00 00 84 03 00 00 00 00 00 00 01 00  55 55 02 0f"));
}

TEST(DeviceBusInfo, WriteRangeErrors) {
  DeviceHarness h;
  struct Case {
    std::vector<std::string> args;
    std::string err;
  } cases[] = {
      {{"--position-max", "70000"}, "--position-max must be 0..65535, got 70000"},
      {{"--servo", "256"}, "--servo must be 0..255, got 256"},
      {{"--led-warning", "smoke"},
       "--led-warning: unknown warning 'smoke'; use a comma list of overheat, overvoltage, "
       "overposition, or none"},
      {{"--servo", "1", "--position-min", "800", "--position-max", "200", "--millivolts-min", "0",
        "--millivolts-max", "0", "--temp-max", "0", "--led", "on", "--led-warning", "none"},
       "position-min 800 is above position-max 200"},
  };
  for (const Case& c : cases) {
    std::vector<std::string> args{"bus-info", "write", "--i-have-one-servo-attached"};
    args.insert(args.end(), c.args.begin(), c.args.end());
    args.insert(args.end(), {"--port", "emu:xarm"});
    RunResult r = h.run(args);
    EXPECT_EQ(r.code, 2) << c.args[0];
    EXPECT_EQ(r.err, "seqc: error: " + c.err + "\n");
  }
  EXPECT_EQ(h.received(), "");
}

}  // namespace
}  // namespace seqc::cli::test
