// `seqc plot` and `seqc simulate` for each kind of program (compiler/formats/program_views.hpp):
// a servo program's positions over time worked out by hand, and the car's stream counted in
// packets; a show's parts stacked on one time axis.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

#include "compiler/compile.hpp"
#include "compiler/formats/program_views.hpp"
#include "compiler/formats/raspblock_simulate.hpp"
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

TEST(ProgramViews, LanesNameTheUnitTheBoardCounts) {
  // The LeArm's LSC-6 board takes pulse widths in microseconds, 500-2500; the xArm's bus servos
  // count 0-1000 of their own units.
  io::DiskFileReader disk;
  const std::string examples = std::string(SEQC_SOURCE_DIR) + "/examples/";
  const compiler::CompileOutput learm = compiler::compile_file(examples + "learm.yaml", disk);
  const compiler::CompileOutput xarm = compiler::compile_file(examples + "walk.yaml", disk);
  ASSERT_TRUE(learm.program && xarm.program);
  const std::string pwm = plot_program(*learm.program, {});
  const std::string bus = plot_program(*xarm.program, {});
  EXPECT_NE(pwm.find("id 1, us<"), std::string::npos);
  EXPECT_EQ(pwm.find(", units<"), std::string::npos);
  EXPECT_NE(bus.find("id 1, units<"), std::string::npos);
}

// The state the preview reads where it changes, from the packets alone, is the state at every
// millisecond: the last change at or before it.
TEST(ProgramViews, TheCarsChangesAreItsStateAtEveryMillisecond) {
  io::DiskFileReader disk;
  const compiler::CompileOutput car =
      compiler::compile_file(std::string(SEQC_SOURCE_DIR) + "/examples/car-dance.yaml", disk);
  ASSERT_NE(car.raspblock_program(), nullptr);
  const CarSimulation every = simulate_car(*car.raspblock_program(), 1);
  const CarSimulation changes = car_changes(*car.raspblock_program());
  ASSERT_FALSE(changes.samples.empty());
  EXPECT_EQ(changes.samples.front().time_ms, 0u);
  std::size_t c = 0;
  for (const CarSimulation::Sample& s : every.samples) {
    while (c + 1 < changes.samples.size() && changes.samples[c + 1].time_ms <= s.time_ms) ++c;
    ASSERT_TRUE(changes.samples[c].state == s.state) << s.time_ms << " ms";
  }
  EXPECT_EQ(c + 1, changes.samples.size());  // none after the end
  EXPECT_LT(changes.samples.size(), every.samples.size() / 10);
}

// Hours-long programs: simulate's default rows, the car's pictures and the comparison with the
// intended curve stay bounded (the steps written here: 6,000 s over 50,000 rows is 120 ms, over
// 10,000 picture samples 600 ms).
TEST(ProgramViews, LongProgramsHaveBoundedViews) {
  MemoryFiles files;
  files.files["car.yaml"] = "robot: raspblock\nsequence:\n  - drive: {x: 15}\n    time: 6000s\n";
  files.files["arm.yaml"] =
      "robot: xarm\nsequence:\n  - move: {base: 500}\n    time: 1s\n"
      "  - move: {base: 700}\n    time: 5999s\n    ease: elastic-out\n";
  const compiler::CompileOutput car = compiler::compile_file("car.yaml", files);
  const compiler::CompileOutput arm = compiler::compile_file("arm.yaml", files);
  ASSERT_NE(car.raspblock_program(), nullptr);
  ASSERT_NE(arm.servo_program(), nullptr);
  EXPECT_EQ(default_simulate_step_ms(*car.program), 120u);
  EXPECT_EQ(default_simulate_step_ms(*arm.program), 120u);
  EXPECT_EQ(default_simulate_step_ms(*compile_try().program), 20u);
  EXPECT_EQ(car_picture_step_ms(*car.raspblock_program()), 600u);
  const Simulated sim = simulate(*arm.program, 120, true);
  EXPECT_EQ(static_cast<std::size_t>(std::count(sim.csv.begin(), sim.csv.end(), '\n')),
            1 + 50'000 + 1);
  ASSERT_EQ(sim.differences.size(), 1u);
  EXPECT_LE(sim.differences[0].largest, 1.0 + 1e-9);
  PlotOptions options;
  EXPECT_LT(plot_program(*car.program, options).size(), 1'000'000u);
  EXPECT_LT(plot_program(*arm.program, options).size(), 200'000u);
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

TEST(ProgramViews, AFilesPageIsItsOnePartOnItsOwnTimeAxis) {
  const compiler::CompileOutput out = compile_try();  // 1750 ms, no song
  ASSERT_TRUE(out.program);
  MemoryFiles files;
  EXPECT_EQ(preview_program(*out.program, "try.yaml, group 0", nullptr, files),
            preview_page("try.yaml, group 0", {""},
                         {*preview_part(*out.program, "try.yaml, group 0", 1750)}, 1750));
  PlotOptions options;
  options.title = "try.yaml, group 0";
  EXPECT_EQ(plot_program(*out.program, options, nullptr), plot_program(*out.program, options));
}

// A song the file reader refuses (over its size limit): embedded as the SongReader's smaller copy
// when it has one; else the page and `missing` say why and how to fix it, and nothing plays.
class BigSong final : public seqc::FileReader {
 public:
  Result<std::string> read(const std::string& path) override {
    if (path == "try.yaml") return std::string(kSongDance);
    return make_error(path + ": file is too large (over 16 MiB)");
  }
  static constexpr const char* kSongDance =
      "robot: xarm\nmusic:\n  file: long.wav\n  downbeat: 0.500s\n  tempo: 120\n"
      "  meter: 4/4\nsequence:\n  - move: {base: 700}\n    time: 1b\n";
};
class Encoder final : public seqc::SongReader {
 public:
  bool can = true;
  Result<seqc::SongSamples> read(const std::string& path) override {
    return make_error(path + ": not decoded here");
  }
  Result<std::string> compressed(const std::string& path) override {
    if (!can) return make_error(path + ": cannot encode");
    return std::string("OggS");
  }
};

TEST(ProgramViews, ASongTooLargeToEmbedIsEmbeddedSmallerOrSaidMissing) {
  BigSong files;
  const compiler::CompileOutput out = compiler::compile_file("try.yaml", files);
  ASSERT_TRUE(out.program);
  Encoder encoder;
  std::string missing = "unset";
  const std::string page = preview_program(*out.program, "try.yaml", &encoder, files, &missing);
  EXPECT_EQ(missing, "");
  EXPECT_NE(
      page.find("<audio id=\"song\" preload=\"auto\" src=\"data:audio/ogg;base64,T2dnUw==\">"),
      std::string::npos);

  encoder.can = false;
  const std::string without = preview_program(*out.program, "try.yaml", &encoder, files, &missing);
  EXPECT_EQ(missing,
            "the song is not in this page (long.wav: file is too large (over 16 MiB); long.wav: "
            "cannot encode): convert it to a smaller file, e.g. `ffmpeg -i long.wav -ac 1 -q:a 3 "
            "song.ogg`, and name that in `music: file:`");
  EXPECT_EQ(without.find("<audio id=\"song\""), std::string::npos);
  EXPECT_NE(without.find("<p class=\"song-missing\">the song is not in this page (long.wav: "),
            std::string::npos);
}

}  // namespace
}  // namespace seqc::compiler
