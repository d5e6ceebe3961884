// `seqc plot` and `seqc simulate` for each kind of program (runtime/boards/program_views.hpp):
// a servo program's positions over time worked out by hand, and the car's stream counted in
// packets.
#include <gtest/gtest.h>

#include <map>
#include <string>

#include "compiler/compile.hpp"
#include "runtime/boards/program_views.hpp"
#include "runtime/io/disk.hpp"

namespace seqc::boards {
namespace {

class MemoryFiles final : public seqc::FileReader {
 public:
  std::map<std::string, std::string> files;
  Result<std::string> read(const std::string& path) override {
    auto it = files.find(path);
    if (it == files.end()) return make_error("no such file");
    return it->second;
  }
};

// Keyframes: 0-500 ms claw to 200 and base to 700, 500-1500 ms elbow to 300, 1500-1750 ms claw
// to 400; every xarm servo starts at its home, 500.
constexpr const char* kProgram = R"(name: try
robot:
  profile: xarm
sequence:
  - move: {claw: 200, base: 700}
    time: 500ms
  - move: {elbow: 300}
    time: 1s
  - move: {claw: 400}
    time: 250ms
)";

compiler::CompileOutput compile_try() {
  MemoryFiles files;
  files.files["try.yaml"] = kProgram;
  return compiler::compile_file("try.yaml", files);
}

TEST(ProgramViews, AServoProgramIsSimulatedFromItsKeyframes) {
  const compiler::CompileOutput out = compile_try();
  ASSERT_NE(out.servo_program(), nullptr);
  const Simulated sim = simulate(out, 1000, false);
  ASSERT_TRUE(sim.ok);
  EXPECT_EQ(sim.steps, 3u);
  EXPECT_EQ(sim.steps_are, "actions");
  EXPECT_EQ(sim.duration_ms, 1750u);
  EXPECT_TRUE(sim.differences.empty());
  // At 1000 ms the first move is done and the elbow is half way from 500 to 300. The xArm's
  // tip (mm) follows: the base at 700 is 48 deg, the elbow at 400 then 300 is 24 then 48 deg
  // (sign -1, 0.24 deg a unit), so r = 246 sin e, z = 72 + 97 + 246 cos e,
  // x = r cos 48 deg, y = r sin 48 deg.
  EXPECT_EQ(sim.csv,
            "time_ms,claw,elbow,base,tip_x,tip_y,tip_z\n"
            "0,500,500,500,0.00,0.00,415.00\n"
            "1000,200,400,700,66.95,74.36,393.73\n"
            "1750,400,300,700,122.33,135.86,333.61\n");
  EXPECT_EQ(length_ms(out), 1750u);
}

TEST(ProgramViews, ComparingGivesEachServoItsLargestDifference) {
  const Simulated sim = simulate(compile_try(), 1000, true);
  ASSERT_TRUE(sim.ok);
  ASSERT_EQ(sim.differences.size(), 3u);
  EXPECT_EQ(sim.csv.substr(0, sim.csv.find('\n')),
            "time_ms,claw,claw_intended,elbow,elbow_intended,base,base_intended,tip_x,tip_y,"
            "tip_z");
}

TEST(ProgramViews, TheCarIsCountedInPackets) {
  io::DiskFileReader disk;
  const compiler::CompileOutput car =
      compiler::compile_file(std::string(SEQC_SOURCE_DIR) + "/examples/car-dance.yaml", disk);
  ASSERT_NE(car.raspblock_program(), nullptr);
  const Simulated sim = simulate(car, 20, false);
  ASSERT_TRUE(sim.ok);
  EXPECT_EQ(sim.steps_are, "packets");
  EXPECT_EQ(sim.steps, car.raspblock_program()->packets.size());
  EXPECT_EQ(sim.duration_ms, car.raspblock_program()->duration_ms);
  EXPECT_EQ(length_ms(car), car.raspblock_program()->duration_ms);
  compiler::PlotOptions options;
  options.title = "car title";
  const std::string svg = plot(car, options);
  EXPECT_EQ(svg.rfind("<svg", 0), 0u);
  EXPECT_NE(svg.find("car title"), std::string::npos);
}

TEST(ProgramViews, NothingWithoutAProgram) {
  const compiler::CompileOutput none;
  EXPECT_FALSE(simulate(none, 20, false).ok);
  EXPECT_EQ(plot(none, {}), "");
  EXPECT_EQ(length_ms(none), 0u);
}

}  // namespace
}  // namespace seqc::boards
