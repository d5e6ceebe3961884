// `seqc offset read|adjust|write` end to end against the emulated controller.
#include <gtest/gtest.h>

#include "tests/cli/device_test_util.hpp"

namespace seqc::cli::test {
namespace {

TEST(DeviceOffset, AdjustIsVolatileUntilWritten) {
  DeviceHarness h;
  RunResult r = h.run({"offset", "adjust", "1", "-20", "--port", "emu:xarm"});
  EXPECT_EQ(r.code, 0) << r.err;
  // 18 servo offsetLo offsetHi: -20 = 0xffec.
  EXPECT_EQ(h.received(), hex("55 55 05 18 01 ec ff  55 55 02 0f"));
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(r.err,
            "seqc: servo 1: offset set to -20 (volatile: lost at power-off unless written with "
            "`seqc offset write 1`)\n");

  h.mark();
  r = h.run({"offset", "read", "1", "2", "--port", "emu:xarm"});
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(h.received(), hex("55 55 05 17 02 01 02"));
  EXPECT_EQ(r.out,
            "servo  offset\n"
            "1      -20\n"
            "2      0\n");

  h.emu.power_cycle(h.clock.now());
  EXPECT_EQ(h.run({"offset", "read", "1", "--port", "emu:xarm"}).out, "servo  offset\n1      0\n");
}

TEST(DeviceOffset, WriteKeepsTheOffsetOverPowerOff) {
  DeviceHarness h;
  ASSERT_EQ(
      h.run({"offset", "adjust", "wrist_roll", "15", "--robot", "xarm", "--port", "emu:xarm"}).code,
      0);
  h.mark();
  RunResult r = h.run({"offset", "write", "2", "--port", "emu:xarm"});
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(h.received(), hex("55 55 04 16 01 02  55 55 02 0f"));
  EXPECT_EQ(r.out, "");
  EXPECT_NE(r.err.find("seqc: servo 2: offset written (kept over power-off)\n"), std::string::npos)
      << r.err;

  h.emu.power_cycle(h.clock.now());
  r = h.run({"offset", "read", "wrist_roll", "--robot", "xarm", "--port", "emu:xarm"});
  EXPECT_EQ(r.out,
            "servo  name        offset\n"
            "2      wrist_roll  15\n");
}

TEST(DeviceOffset, OutOfRangeOffsetsAreUsageErrors) {
  DeviceHarness h;
  RunResult r = h.run({"offset", "adjust", "1", "40000", "--port", "emu:xarm"});
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err, "seqc: error: offset must be -32768..32767, got 40000\n");
  r = h.run({"offset", "adjust", "1", "-129", "--port", "emu:xarm"});
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err,
            "seqc: error: offset must be -128..127, got -129 (ServoOffsetRead reports offsets as "
            "a signed byte)\n");
  r = h.run({"offset", "adjust", "1", "2x", "--port", "emu:xarm"});
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err, "seqc: error: offset: '2x' is not a whole number\n");
  EXPECT_EQ(h.received(), "");
}

}  // namespace
}  // namespace seqc::cli::test
