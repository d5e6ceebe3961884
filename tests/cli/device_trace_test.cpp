// `--trace FILE` on the commands that talk to a board other than upload (servo, battery, group,
// play; offset, bus-info and teach share the same option through add_device_options): every byte
// both ways in the format of docs/trace.md, with the board's dialect named, and `seqc decode`
// reads the file back. The harness's emulated controller is unpaced (XArmConfig{}: bytes take no
// time on its line), so every event of these short exchanges is at t=0.000000.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "tests/cli/device_test_util.hpp"

namespace seqc::cli::test {
namespace {

namespace fs = std::filesystem;

std::string slurp(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / "seqc-device-trace-test";
  fs::create_directories(dir);
  fs::remove(dir / name);
  return dir / name;
}

// The trace is decoded in-process, from the same files the harness reads.
RunResult decode(DeviceHarness& h, const fs::path& trace) {
  h.files.add(trace.string(), slurp(trace));
  return h.run({"decode", trace.string()});
}

TEST(DeviceTrace, ServoMoveIsTracedAndDecoded) {
  DeviceHarness h;
  const fs::path trace = scratch("move.trace");
  RunResult r = h.run({"servo", "move", "1=300", "--port", "emu:xarm", "--trace", trace.string()});
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string text = slurp(trace);
  // The header, the dialect, then the move (10 bytes) and the battery check after it.
  EXPECT_EQ(text,
            "# seqc trace of emu:xarm; t in seconds, > to the device, < from it\n"
            "# dialect: xArm / LSC-16 / LSC-32\n"
            "t=0.000000 > 55 55 08 03 01 e8 03 01 2c 01\n"
            "t=0.000000 > 55 55 02 0f\n"
            "t=0.000000 < 55 55 04 0f 4c 1d\n");
  RunResult d = decode(h, trace);
  EXPECT_EQ(d.code, 0) << d.err;
  EXPECT_EQ(d.out,
            "# trace, xArm / LSC-16 / LSC-32 dialect\n"
            "t=0.000000 > MultiServoMove time_ms=1000 servos=[{id=1 position=300}]\n"
            "t=0.000000 > GetBatteryVoltage\n"
            "t=0.000000 < BatteryVoltage millivolts=7500\n"
            "# 3 frame(s), 0 issue(s)\n");
}

TEST(DeviceTrace, BatteryIsTraced) {
  DeviceHarness h;
  const fs::path trace = scratch("battery.trace");
  RunResult r = h.run({"battery", "--port", "emu:xarm", "--trace", trace.string()});
  ASSERT_EQ(r.code, 0) << r.err;
  RunResult d = decode(h, trace);
  EXPECT_EQ(d.out,
            "# trace, xArm / LSC-16 / LSC-32 dialect\n"
            "t=0.000000 > GetBatteryVoltage\n"
            "t=0.000000 < BatteryVoltage millivolts=7500\n"
            "# 2 frame(s), 0 issue(s)\n");
}

// An LSC-6 session without a download: only the trace's dialect line says which dialect its
// 55 55 02 06 is (the xArm dialect would read it as a GroupStarted without its data).
TEST(DeviceTrace, AnLsc6SessionDecodesInItsOwnDialect) {
  DeviceHarness h;
  const fs::path trace = scratch("lsc6.trace");
  RunResult r = h.run(
      {"group", "run", "3", "--robot", "lsc-6", "--port", "emu:lsc6", "--trace", trace.string()});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(slurp(trace).find("# dialect: LSC-6\n"), std::string::npos);
  RunResult d = decode(h, trace);
  EXPECT_EQ(d.code, 0) << d.out << d.err;
  EXPECT_EQ(d.out.substr(0, d.out.find('\n')), "# trace, LSC-6 dialect");
  EXPECT_NE(d.out.find("# 2 frame(s), 0 issue(s)"), std::string::npos) << d.out;
}

TEST(DeviceTrace, PlayIsTraced) {
  DeviceHarness h;
  h.files.add("one.yaml", R"(name: one
robot: xarm
sequence:
  - move: {claw: 300}
    time: 1s
)");
  const fs::path trace = scratch("play.trace");
  RunResult r = h.run({"play", "one.yaml", "--port", "emu:xarm", "--trace", trace.string()});
  ASSERT_EQ(r.code, 0) << r.err;
  RunResult d = decode(h, trace);
  // The first-move read (the claw, at the emulator's 500), the probe and its answer, then the
  // move at its start.
  EXPECT_EQ(d.out,
            "# trace, xArm / LSC-16 / LSC-32 dialect\n"
            "t=0.000000 > ServoPositionRead servos=[1]\n"
            "t=0.000000 < ServoPositions servos=[{id=1 position=500}]\n"
            "t=0.000000 > GetBatteryVoltage\n"
            "t=0.000000 < BatteryVoltage millivolts=7500\n"
            "t=0.000000 > MultiServoMove time_ms=1000 servos=[{id=1 position=300}]\n"
            "# 5 frame(s), 0 issue(s)\n");
}

// A trace file that cannot be written stops the command before the port is opened.
TEST(DeviceTrace, AnUnwritableTraceSendsNothing) {
  DeviceHarness h;
  RunResult r =
      h.run({"servo", "move", "1=300", "--port", "emu:xarm", "--trace", "/no/such/dir/move.trace"});
  EXPECT_EQ(r.code, 5);
  EXPECT_EQ(r.err, "seqc: error: --trace /no/such/dir/move.trace: cannot write the file\n");
  EXPECT_EQ(h.received(), "");
}

}  // namespace
}  // namespace seqc::cli::test
