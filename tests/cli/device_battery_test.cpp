// `seqc battery`, and what every device command does when the controller does not answer.
#include <gtest/gtest.h>

#include "tests/cli/device_test_util.hpp"

namespace seqc::cli::test {
namespace {

TEST(DeviceBattery, PrintsMillivoltsAndVolts) {
  emu::XArmConfig config;
  config.battery_mv = 7496;  // rounds to 7.50 V
  DeviceHarness h(config);
  RunResult r = h.run({"battery", "--port", "emu:xarm"});
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(h.received(), hex("55 55 02 0F"));
  EXPECT_EQ(r.out, "7496 mV (7.50 V)\n");
  EXPECT_EQ(r.err, "");
}

TEST(DeviceBattery, NoReplyIsADeviceFailureAfterTheTimeout) {
  emu::XArmConfig config;
  config.faults.silent_after = 0;
  DeviceHarness h(config);
  const io::TimePoint start = h.clock.now();
  RunResult r = h.run({"battery", "--port", "emu:xarm", "--timeout", "300ms"});
  EXPECT_EQ(r.code, 4);
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(r.err,
            "seqc: error: no reply from the controller on emu:xarm within 300 ms (waiting for "
            "the battery voltage); check that the controller is powered and connected, and "
            "--port\n");
  EXPECT_EQ(h.clock.now() - start, std::chrono::milliseconds(300));
}

TEST(DeviceBattery, UnansweredCommandIsConfirmedTwiceThenFails) {
  emu::XArmConfig config;
  config.faults.silent_after = 0;
  DeviceHarness h(config);
  RunResult r = h.run({"servo", "off", "1", "--port", "emu:xarm"});
  EXPECT_EQ(r.code, 4);
  EXPECT_EQ(h.received(), hex("55 55 04 14 01 01  55 55 02 0f  55 55 02 0f"));
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(r.err,
            "seqc: error: no reply from the controller on emu:xarm: MultiServoOff servos=[1] has "
            "no answer of its own, and the battery check sent after it went unanswered (sent 2 "
            "times, 1 s each), so it may not have arrived; check that the controller is powered "
            "and connected, and --port\n");
}

TEST(DeviceBattery, HangUpIsReportedAsSuch) {
  emu::XArmConfig config;
  config.faults.hangup_at = 1;
  DeviceHarness h(config);
  RunResult r = h.run({"battery", "--port", "emu:xarm"});
  EXPECT_EQ(r.code, 4);
  EXPECT_NE(r.err.find("seqc: error: the controller on emu:xarm went away"), std::string::npos)
      << r.err;
}

TEST(DeviceBattery, BadTimeoutAndPortAreUsageErrors) {
  DeviceHarness h;
  RunResult r = h.run({"battery", "--port", "emu:xarm", "--timeout", "0s"});
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err, "seqc: error: --timeout must be more than 0 and at most 1 hour, got '0s'\n");
  r = h.run({"battery", "--port", "emu:xarm", "--timeout", "5"});
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err, "seqc: error: --timeout: time '5' has no unit; write '5ms' or '5s'\n");
  // A reply is waited for in clock time: no beats offered, none taken.
  for (const char* t : {"abc", "2b", "1bar"}) {
    r = h.run({"battery", "--port", "emu:xarm", "--timeout", t});
    EXPECT_EQ(r.code, 2);
    EXPECT_EQ(r.err, std::string("seqc: error: --timeout: '") + t +
                         "' is not a time in ms or s; write it like '500ms' or '2s'\n");
  }
  r = h.run({"battery", "--port", "emu:raspblock"});
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(h.received(), "");
}

}  // namespace
}  // namespace seqc::cli::test
