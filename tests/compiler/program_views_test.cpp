// `seqc plot` and `seqc simulate` for each kind of program (compiler/formats/program_views.hpp):
// a servo program's positions over time worked out by hand, and the car's stream counted in
// packets; a show's parts stacked on one time axis.
#include <gtest/gtest.h>

#include <cstdlib>
#include <map>
#include <string>
#include <vector>

#include "compiler/compile.hpp"
#include "compiler/formats/program_views.hpp"
#include "runtime/io/disk.hpp"
#include "tests/compiler/lang_test_util.hpp"

namespace seqc::compiler {
namespace {

using testing::MemoryFiles;

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
  const Simulated sim = simulate(*out.program, 1000, false);
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
  EXPECT_EQ(length_ms(*out.program), 1750u);
}

TEST(ProgramViews, ComparingGivesEachServoItsLargestDifference) {
  const Simulated sim = simulate(*compile_try().program, 1000, true);
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
  const Simulated sim = simulate(*car.program, 20, false);
  ASSERT_TRUE(sim.ok);
  EXPECT_EQ(sim.steps_are, "packets");
  EXPECT_EQ(sim.steps, car.raspblock_program()->packets.size());
  EXPECT_EQ(sim.duration_ms, car.raspblock_program()->duration_ms);
  EXPECT_EQ(length_ms(*car.program), car.raspblock_program()->duration_ms);
  PlotOptions options;
  options.title = "car title";
  const std::string svg = plot_program(*car.program, options);
  EXPECT_EQ(svg.rfind("<svg", 0), 0u);
  EXPECT_NE(svg.find("car title"), std::string::npos);
}

// A second performer for the shows: the claw to 300 over 500 ms.
compiler::CompileOutput compile_short() {
  MemoryFiles files;
  files.files["short.yaml"] =
      "robot:\n  profile: xarm\nsequence:\n  - move: {claw: 300}\n"
      "    time: 500ms\n";
  return compiler::compile_file("short.yaml", files);
}

TEST(ProgramViews, AShowStacksItsPartsOnTheLongestPartsTimeAxis) {
  const compiler::CompileOutput long_one = compile_try();     // 1750 ms
  const compiler::CompileOutput short_one = compile_short();  // 500 ms
  ASSERT_TRUE(long_one.program && short_one.program);
  const std::string svg = plot_show({{&*long_one.program, "arm: try.yaml", "arm"},
                                     {&*short_one.program, "other: short.yaml", "other"}},
                                    "duet & co.yaml", "duet", {});
  // Each part is its own picture over 0-1750 ms, moved down under the one before it.
  PlotOptions window;
  window.from_ms = 0;
  window.to_ms = 1750;
  window.title = "arm: try.yaml";
  std::string first = plot_program(*long_one.program, window);
  window.title = "other: short.yaml";
  std::string second = plot_program(*short_one.program, window);
  const auto height = [](const std::string& part) {
    return std::atoi(part.c_str() + part.find("height=\"") + 8);
  };
  const int second_y = 36 + height(first) + 10;
  const int total = second_y + height(second) + 10;
  first.insert(4, " y=\"36\"");
  second.insert(4, " y=\"" + std::to_string(second_y) + "\"");
  const std::string size = std::to_string(total);
  EXPECT_EQ(svg, "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"1100\" height=\"" + size +
                     "\" viewBox=\"0 0 1100 " + size +
                     "\" font-family=\"sans-serif\">\n<title>duet &amp; co.yaml</title>\n"
                     "<rect width=\"1100\" height=\"" +
                     size +
                     "\" fill=\"#ffffff\"/>\n<text x=\"12\" y=\"24\" font-size=\"17\" "
                     "font-weight=\"bold\">show duet (2 performers, one clock)</text>\n" +
                     first + second + "</svg>\n");
}

TEST(ProgramViews, AShowsPageDrawsEveryPartOnTheLongestPartsTimeAxis) {
  const compiler::CompileOutput long_one = compile_try();     // 1750 ms
  const compiler::CompileOutput short_one = compile_short();  // 500 ms
  ASSERT_TRUE(long_one.program && short_one.program);
  const std::string page = preview_show({{&*long_one.program, "try.yaml, group 0", "arm"},
                                         {&*short_one.program, "short.yaml, group 1", "hand"}},
                                        "duet.yaml", "duet");
  std::vector<PreviewPart> parts;
  parts.push_back(*preview_part(*long_one.program, "try.yaml, group 0", 1750));
  parts.push_back(*preview_part(*short_one.program, "short.yaml, group 1", 1750));
  EXPECT_EQ(page, preview_page("show duet (2 performers, one clock), duet.yaml", {"arm", "hand"},
                               parts, 1750));
}

}  // namespace
}  // namespace seqc::compiler
