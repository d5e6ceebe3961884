// seqc teach and `servo read --format yaml` in-process against the emulated controller. The
// person at the robot is played by the standard input: before each line is read, the test moves
// limp servos "by hand" in the emulator, so every recorded pose is different and known.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <functional>
#include <istream>
#include <streambuf>
#include <string>
#include <utility>
#include <vector>

#include "tests/cli/device_test_util.hpp"

namespace seqc::cli::test {
namespace {

// Lines of input, each preceded by an action run when the program asks for that line.
class PersonAtTheRobot final : public std::streambuf {
 public:
  void then(std::function<void()> before, std::string line) {
    steps_.emplace_back(std::move(before), std::move(line) + "\n");
  }

 protected:
  int_type underflow() override {
    if (next_ == steps_.size()) return traits_type::eof();
    auto& [before, line] = steps_[next_++];
    if (before) before();
    setg(line.data(), line.data(), line.data() + line.size());
    return traits_type::to_int_type(line[0]);
  }

 private:
  std::vector<std::pair<std::function<void()>, std::string>> steps_;
  std::size_t next_ = 0;
};

constexpr const char* kFile =
    "# an arm routine\n"
    "robot: xarm   # the stock arm\n"
    "\n"
    "poses:\n"
    "  ready: {claw: 300, elbow: 650}   # kept as written\n"
    "\n"
    "sequence:\n"
    "  - move: ready\n"
    "    time: 1s\n";

TEST(DeviceTeach, EachEnterAddsTheHandPosedPoseAndKeepsTheFileAsWritten) {
  DeviceHarness h;
  const std::string path = ::testing::TempDir() + "teach-" + std::to_string(::getpid()) + ".yaml";
  std::ofstream(path) << kFile;
  h.files.add(path, kFile);
  PersonAtTheRobot person;
  auto by_hand = [&h](std::uint8_t id, std::uint16_t p) {
    EXPECT_TRUE(h.emu.pose_by_hand(id, p, h.clock.now())) << "servo " << int{id} << " is not limp";
  };
  person.then([&] { by_hand(1, 200), by_hand(6, 800); }, "");  // Enter: record
  person.then({}, "");                                         // name: the default
  person.then([&] { by_hand(4, 720), by_hand(5, 330); }, "");  // Enter
  person.then({}, "reach");                                    // name
  person.then({}, "q");
  std::istream in(&person);
  h.in = &in;
  const RunResult r = h.run({"teach", path, "--port", "emu:xarm"});
  ASSERT_EQ(r.code, 0) << r.err;
  // MultiServoOff for servos 1-6 first (03 is not sent: nothing moves), then two reads.
  EXPECT_EQ(h.received().substr(0, 32), hex("55 55 09 14 06 01 02 03 04 05 06"));
  std::ifstream written(path);
  const std::string text((std::istreambuf_iterator<char>(written)),
                         std::istreambuf_iterator<char>());
  EXPECT_EQ(text,
            "# an arm routine\n"
            "robot: xarm   # the stock arm\n"
            "\n"
            "poses:\n"
            "  ready: {claw: 300, elbow: 650}   # kept as written\n"
            "  pose1: {claw: 200, wrist_roll: 500, wrist_pitch: 500, elbow: 500, shoulder: 500, "
            "base: 800}\n"
            "  reach: {claw: 200, wrist_roll: 500, wrist_pitch: 500, elbow: 720, shoulder: 330, "
            "base: 800}\n"
            "\n"
            "sequence:\n"
            "  - move: ready\n"
            "    time: 1s\n");
  EXPECT_NE(r.err.find("seqc: 2 poses added to"), std::string::npos) << r.err;
  std::remove(path.c_str());
}

TEST(DeviceTeach, PoweredServosHoldAgainstTheHand) {
  DeviceHarness h;
  EXPECT_FALSE(h.emu.pose_by_hand(1, 200, h.clock.now()));
  ASSERT_EQ(h.run({"servo", "off", "1", "--port", "emu:xarm"}).code, 0);
  EXPECT_TRUE(h.emu.pose_by_hand(1, 200, h.clock.now()));
}

TEST(DeviceTeach, PwmBoardsCannotBeTaught) {
  DeviceHarness h;
  h.files.add("pwm.yaml", "robot: lsc-16\nsequence:\n  - move: home\n    time: 1s\n");
  const RunResult r = h.run({"teach", "pwm.yaml", "--port", "emu:xarm"});
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("PWM servos, which cannot report where they are"), std::string::npos);
  EXPECT_EQ(h.received(), "");
}

TEST(DeviceServo, ReadAsYamlGivesAPoseToPaste) {
  emu::XArmConfig config;
  config.initial_positions = {{1, 300}, {6, 720}};
  DeviceHarness h(config);
  RunResult r = h.run({"servo", "read", "--format", "yaml", "--port", "emu:xarm"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.out,
            "  pose1: {claw: 300, wrist_roll: 500, wrist_pitch: 500, elbow: 500, shoulder: 500, "
            "base: 720}\n");
  r = h.run({"servo", "read", "claw", "base", "--robot", "xarm", "--format", "yaml", "--name",
             "grip", "--port", "emu:xarm"});
  EXPECT_EQ(r.out, "  grip: {claw: 300, base: 720}\n");
}

}  // namespace
}  // namespace seqc::cli::test
