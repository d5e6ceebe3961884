// `seqc group run|stop|erase|speed` end to end against the emulated controller.
#include <gtest/gtest.h>

#include "tests/cli/device_test_util.hpp"

namespace seqc::cli::test {
namespace {

TEST(DeviceGroup, RunSendsGroupRunThenTheCheckAndReportsTheStart) {
  DeviceHarness h;
  h.store_group_3();
  RunResult r = h.run({"group", "run", "3", "--times", "2", "--port", "emu:xarm"});
  EXPECT_EQ(r.code, 0) << r.err;
  // GroupRun: 06 group timesLo timesHi; then GetBatteryVoltage.
  EXPECT_EQ(h.received(), hex("55 55 05 06 03 02 00  55 55 02 0f"));
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(r.err, "seqc: group 3 started, 2 times\n");
  EXPECT_EQ(h.emu.playing_group(), std::optional<std::uint8_t>(3));
}

TEST(DeviceGroup, RunForeverSendsZeroTimes) {
  DeviceHarness h;
  h.store_group_3();
  RunResult r = h.run({"group", "run", "3", "--forever", "--port", "emu:xarm"});
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(h.received(), hex("55 55 05 06 03 00 00  55 55 02 0f"));
  EXPECT_EQ(r.out, "");
  EXPECT_NE(r.err.find("seqc: group 3 started, looping until `seqc group stop`\n"),
            std::string::npos)
      << r.err;
}

TEST(DeviceGroup, RunOfAnEmptyGroupWarns) {
  DeviceHarness h;
  RunResult r = h.run({"group", "run", "4", "--port", "emu:xarm"});
  EXPECT_EQ(r.code, 0);
  EXPECT_EQ(h.received(), hex("55 55 05 06 04 01 00  55 55 02 0f"));
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(r.err,
            "seqc: group 4: run sent, 1 time\n"
            "seqc: warning: the controller did not report group 4 starting; it may be empty "
            "(store one with `seqc upload`)\n");
}

TEST(DeviceGroup, RunRangeErrorsSendNothing) {
  DeviceHarness h;
  RunResult r = h.run({"group", "run", "3", "--times", "0", "--port", "emu:xarm"});
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err,
            "seqc: error: --times must be 1..65535, got 0 (--forever loops until `seqc group "
            "stop`)\n");
  r = h.run({"group", "run", "255", "--port", "emu:xarm"});
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err,
            "seqc: error: group must be 0..254, got 255 (255 means every group on the wire; say "
            "`all` where a command allows it)\n");
  r = h.run({"group", "run", "3", "--times", "65536", "--port", "emu:xarm"});
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(h.received(), "");
}

TEST(DeviceGroup, StopStopsThePlayingGroup) {
  DeviceHarness h;
  h.store_group_3();
  ASSERT_EQ(h.run({"group", "run", "3", "--forever", "--port", "emu:xarm"}).code, 0);
  h.mark();
  RunResult r = h.run({"group", "stop", "--port", "emu:xarm"});
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(h.received(), hex("55 55 02 07  55 55 02 0f"));
  EXPECT_EQ(r.out, "");
  EXPECT_NE(r.err.find("seqc: stopped\n"), std::string::npos) << r.err;
  EXPECT_EQ(h.emu.playing_group(), std::nullopt);
}

TEST(DeviceGroup, EraseOneAndAll) {
  DeviceHarness h;
  h.store_group_3();
  RunResult r = h.run({"group", "erase", "3", "--port", "emu:xarm"});
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(h.received(), hex("55 55 03 08 03"));  // answered by 55 55 02 08: no check needed
  EXPECT_EQ(r.out, "");
  EXPECT_NE(r.err.find("seqc: group 3 erased\n"), std::string::npos) << r.err;
  EXPECT_FALSE(h.emu.stored_group(3).has_value());

  h.mark();
  r = h.run({"group", "erase", "all", "--port", "emu:xarm"});
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(h.received(), hex("55 55 03 08 ff"));
  EXPECT_EQ(r.out, "");
  EXPECT_NE(r.err.find("seqc: every group erased\n"), std::string::npos) << r.err;
}

TEST(DeviceGroup, EraseRefusesANumberForAll) {
  DeviceHarness h;
  RunResult r = h.run({"group", "erase", "255", "--port", "emu:xarm"});
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(h.received(), "");
  r = h.run({"group", "erase", "-1", "--port", "emu:xarm"});
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err,
            "seqc: error: group must be 0..254, got -1 (255 means every group on the wire; say "
            "`all` where a command allows it)\n");
}

TEST(DeviceGroup, SpeedOneAndAll) {
  DeviceHarness h;
  RunResult r = h.run({"group", "speed", "3", "150", "--port", "emu:xarm"});
  EXPECT_EQ(r.code, 0) << r.err;
  // GroupSpeed: 0b group pctLo pctHi (150 = 0x96).
  EXPECT_EQ(h.received(), hex("55 55 05 0b 03 96 00  55 55 02 0f"));
  EXPECT_EQ(r.out, "");
  EXPECT_NE(r.err.find("seqc: group 3 speed 150% (volatile: back to 100% at power-off)\n"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(h.emu.group_speed(3), 150);

  h.mark();
  r = h.run({"group", "speed", "all", "300", "--port", "emu:xarm"});
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(h.received(), hex("55 55 05 0b ff 2c 01  55 55 02 0f"));
  EXPECT_EQ(r.out, "");
  EXPECT_NE(r.err.find("seqc: every group speed 300% (volatile: back to 100% at power-off)\n"),
            std::string::npos)
      << r.err;
}

TEST(DeviceGroup, SpeedOutOfRangeIsAUsageError) {
  DeviceHarness h;
  RunResult r = h.run({"group", "speed", "3", "70000", "--port", "emu:xarm"});
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err,
            "seqc: error: percent must be a whole number 1..65535 (100 = as stored), got "
            "'70000'\n");
  r = h.run({"group", "speed", "3", "0", "--port", "emu:xarm"});
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err,
            "seqc: error: percent must be a whole number 1..65535 (100 = as stored), got '0'\n");
  // Not a number: the same words as a number out of range, not the option parser's.
  r = h.run({"group", "speed", "3", "abc", "--port", "emu:xarm"});
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err,
            "seqc: error: percent must be a whole number 1..65535 (100 = as stored), got "
            "'abc'\n");
  EXPECT_EQ(h.received(), "");
}

}  // namespace
}  // namespace seqc::cli::test
