// Runs the built seqc binary and compares its output with golden files.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "tests/cli/seqc_run.hpp"

namespace {

namespace fs = std::filesystem;
using seqc::testing::expect_golden;
using seqc::testing::kCliGolden;
using seqc::testing::kGolden;
using seqc::testing::kSource;
using seqc::testing::seqc;
using seqc::testing::SeqcRun;
using seqc::testing::slurp;

std::vector<fs::path> files_matching(const fs::path& dir, const std::string& prefix,
                                     const std::string& ext) {
  std::vector<fs::path> out;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (name.rfind(prefix, 0) == 0 && e.path().extension() == ext) out.push_back(e.path());
  }
  std::sort(out.begin(), out.end());
  return out;
}

// "# args: --strict" on the first line of a bad-*.yaml adds options to `seqc check`.
std::string extra_args(const fs::path& yaml) {
  std::ifstream in(yaml);
  std::string first;
  std::getline(in, first);
  const std::string marker = "# args: ";
  return first.rfind(marker, 0) == 0 ? first.substr(marker.size()) + " " : "";
}

TEST(BadFiles, EachHasItsExactDiagnostics) {
  const auto bad = files_matching(kGolden, "bad-", ".yaml");
  ASSERT_GE(bad.size(), 30u);
  for (const fs::path& yaml : bad) {
    SCOPED_TRACE(yaml.filename().string());
    const std::string name = yaml.filename().string();
    SeqcRun r = seqc(kGolden, "check " + extra_args(yaml) + name);
    EXPECT_EQ(r.status, 1);
    EXPECT_EQ(r.out.rfind(name + ": ", 0), 0u) << r.out;
    EXPECT_EQ(r.out.find(": ok"), std::string::npos) << r.out;
    EXPECT_NE(r.err.find(": error: "), std::string::npos);
    expect_golden(yaml.parent_path() / (yaml.stem().string() + ".stderr"), r.err);
  }
}

TEST(Examples, CheckCleanly) {
  const auto examples = files_matching(kSource / "examples", "", ".yaml");
  ASSERT_GE(examples.size(), 3u);
  for (const fs::path& yaml : examples) {
    const std::string rel = "examples/" + yaml.filename().string();
    SCOPED_TRACE(rel);
    SeqcRun r = seqc(kSource, "check --strict " + rel);
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.err, "");
    // A stored group's budget line (1,020 actions, or 255 on an LSC-6), or a streamed
    // program's packet count; no warning.
    const bool budget = r.out.rfind(rel + ": ", 0) == 0 &&
                        (r.out.find("/1020 actions, ") != std::string::npos ||
                         r.out.find("/255 actions, ") != std::string::npos) &&
                        r.out.find(" s, fit within ") != std::string::npos;
    const bool stream = r.out.rfind(rel + ": ok (", 0) == 0;
    EXPECT_TRUE(budget || stream) << r.out;
    EXPECT_EQ(r.out.find("warning"), std::string::npos) << r.out;
  }
}

TEST(Examples, ListingsAndHexMatchGoldens) {
  for (const char* name : {"walk", "wave", "dance", "waltz"}) {
    SCOPED_TRACE(name);
    // walk's goldens are of the joint-position fixture (examples/walk.yaml places the tip).
    const std::string rel = std::string(name) == "walk" ? std::string("tests/data/walk-joints.yaml")
                                                        : std::string("examples/") + name + ".yaml";
    SeqcRun listing = seqc(kSource, "compile --emit listing " + rel);
    EXPECT_EQ(listing.status, 0) << listing.err;
    expect_golden(kGolden / "examples" / (std::string(name) + ".listing"), listing.out);
    SeqcRun hex = seqc(kSource, "compile " + rel);
    EXPECT_EQ(hex.status, 0) << hex.err;
    expect_golden(kGolden / "examples" / (std::string(name) + ".hex"), hex.out);
  }
}

// examples/sway.yaml performs one section three times with expressions of its parameters; the
// targets and times below are worked out by hand from the file (tempo 120: a beat is 500 ms).
TEST(Examples, SwayWorksOutItsExpressions) {
  SeqcRun r = seqc(kSource, "compile --emit listing examples/sway.yaml");
  ASSERT_EQ(r.status, 0) << r.err;
  std::vector<std::string> actions;
  std::istringstream in(r.out);
  for (std::string line; std::getline(in, line);) {
    const auto from = line.find(" from examples/sway.yaml:");
    if (line.rfind("  action ", 0) != 0 || from == std::string::npos) continue;
    const auto colon = line.find(": ", from);
    actions.push_back(line.substr(2, from - 2) + line.substr(colon));
  }
  const std::vector<std::string> expected{
      "action 1 at 0 ms: claw(1)=500 wrist_roll(2)=500 wrist_pitch(3)=500 elbow(4)=500 "
      "shoulder(5)=500 base(6)=500",
      // swing 100, lift 60: out by +100 / +60, across by -200 / -120, back by +100 to 500 + 30
      "action 2 at 2000 ms: wrist_pitch(3)=560 base(6)=600",
      "action 3 at 2500 ms: wrist_pitch(3)=440 base(6)=400",
      "action 4 at 3500 ms: wrist_pitch(3)=530 base(6)=500",
      // swing -150, lift 40: out by -150 / +40, across by +300 / -80, back by -150 to 500 + 20
      "action 5 at 4000 ms: wrist_pitch(3)=570 base(6)=350",
      "action 6 at 4500 ms: wrist_pitch(3)=490 base(6)=650",
      "action 7 at 5500 ms: wrist_pitch(3)=520 base(6)=500",
      // swing 60 on half beats: 250 ms, 500 ms, 250 ms
      "action 8 at 6000 ms: wrist_pitch(3)=580 base(6)=560",
      "action 9 at 6250 ms: wrist_pitch(3)=460 base(6)=440",
      "action 10 at 6750 ms: wrist_pitch(3)=530 base(6)=500",
      "action 11 at 7000 ms: claw(1)=500 wrist_roll(2)=500 wrist_pitch(3)=500 elbow(4)=500 "
      "shoulder(5)=500 base(6)=500"};
  EXPECT_EQ(actions, expected) << r.out;
}

TEST(Help, GoldenForSeqcAndItsSubcommands) {
  SeqcRun top = seqc(kSource, "--help");
  EXPECT_EQ(top.status, 0);
  expect_golden(kCliGolden / "help.txt", top.out);
  for (const char* sub : {"check", "compile", "decode", "simulate", "upload", "play", "ports"}) {
    SCOPED_TRACE(sub);
    SeqcRun r = seqc(kSource, std::string(sub) + " --help");
    EXPECT_EQ(r.status, 0);
    expect_golden(kCliGolden / (std::string(sub) + "-help.txt"), r.out);
  }
}

TEST(Check, SummarisesEveryFileAndFailsIfAnyIsBad) {
  SeqcRun r = seqc(
      kSource,
      "check tests/data/walk-joints.yaml tests/golden/bad-unknown-pose.yaml examples/wave.yaml");
  EXPECT_EQ(r.status, 1);
  expect_golden(kCliGolden / "check-several.stdout", r.out);
}

// A file whose only curves are `path: line` moves gives its fit as the tip's distance in mm (its
// joints' pieces are exact: "0 units" would say nothing); one with eased joints as well gives
// both; one without a line keeps the units alone (check-several.stdout).
TEST(Check, LineMovesGiveTheTipsErrorInMillimetres) {
  SeqcRun r = seqc(kSource, "check tests/data/tip-lines.yaml examples/walk.yaml");
  EXPECT_EQ(r.status, 0) << r.err;
  expect_golden(kCliGolden / "check-tip-lines.stdout", r.out);
}

TEST(Check, UnreadableFileIsAFileError) {
  SeqcRun r = seqc(kSource, "check examples/no-such.yaml");
  EXPECT_EQ(r.status, 5);
  EXPECT_EQ(r.err, "seqc: error: examples/no-such.yaml: No such file or directory\n");
  EXPECT_EQ(r.out, "");
}

TEST(Check, WarningPassesUnlessStrict) {
  const std::string file = "tests/golden/bad-speed-strict.yaml";
  SeqcRun lenient = seqc(kSource, "check " + file);
  EXPECT_EQ(lenient.status, 0);
  expect_golden(kCliGolden / "check-warning.stderr", lenient.err);
  expect_golden(kCliGolden / "check-warning.stdout", lenient.out);
  SeqcRun strict = seqc(kSource, "check --strict " + file);
  EXPECT_EQ(strict.status, 1);
}

TEST(Compile, JsonGolden) {
  SeqcRun r = seqc(kSource, "compile --emit json --group 3 tests/data/walk-joints.yaml");
  EXPECT_EQ(r.status, 0) << r.err;
  expect_golden(kCliGolden / "walk-group3.json", r.out);
}

// At 120 bpm `at: 4b` is 2 s: home takes 0-1 s, a hold of every servo 1-2 s, then base. The
// hold was written by no step, so its line says it is a hold (it used to read "from :").
TEST(Compile, AHoldBeforeACueSaysItIsAHold) {
  SeqcRun r = seqc(kSource, "compile --emit listing tests/cli/data/hold-before-cue.yaml");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("\n  action 2 at 1000 ms, a hold: claw(1)=500 wrist_roll(2)=500 "
                       "wrist_pitch(3)=500 elbow(4)=500 shoulder(5)=500 base(6)=500\n"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("\n  action 3 at 2000 ms from tests/cli/data/hold-before-cue.yaml:7:5: "
                       "base(6)=600\n"),
            std::string::npos)
      << r.out;
  EXPECT_EQ(r.out.find("from :"), std::string::npos);
}

TEST(Compile, AShowFileSaysItIsAShowAndHowToRunIt) {
  // compile takes one robot's choreography; a show file gets a located error and a note.
  SeqcRun r = seqc(kSource, "compile examples/duet.yaml");
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.out, "");
  expect_golden(kCliGolden / "compile-show-file.stderr", r.err);
}

TEST(Check, ABinaryFileIsOneErrorAndItsBytesAreNotPrinted) {
  // tests/golden/bad-not-a-text-file.yaml holds NUL, 0x01, an escape sequence and 0xFF on its
  // third line: none of them may reach the terminal.
  SeqcRun r = seqc(kSource, "check tests/golden/bad-not-a-text-file.yaml");
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.err,
            "tests/golden/bad-not-a-text-file.yaml:3:22: error: not a text file (byte 0x00 at "
            "offset 43)\n");
  for (const char c : r.out + r.err) {
    EXPECT_TRUE(c == '\n' || (c >= 0x20 && c < 0x7F)) << static_cast<int>(c);
  }
}

TEST(Compile, WritesOutputOnlyOnSuccess) {
  const fs::path out = fs::path(SEQC_BINARY_DIR) / "tests/cli/tmp/compile-out.hex";
  fs::create_directories(out.parent_path());
  fs::remove(out);
  SeqcRun bad =
      seqc(kSource, "compile tests/golden/bad-unknown-pose.yaml -o '" + out.string() + "'");
  EXPECT_EQ(bad.status, 1);
  EXPECT_FALSE(fs::exists(out));
  SeqcRun good = seqc(kSource, "compile tests/data/walk-joints.yaml -o '" + out.string() + "'");
  EXPECT_EQ(good.status, 0) << good.err;
  EXPECT_EQ(good.out, "");
  EXPECT_EQ(slurp(out), slurp(kGolden / "examples/walk.hex"));
}

TEST(Compile, BadOptionIsAUsageError) {
  SeqcRun r = seqc(kSource, "compile --emit pdf tests/data/walk-joints.yaml");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err.rfind("seqc: error: ", 0), 0u) << r.err;
  SeqcRun g = seqc(kSource, "compile --group 255 tests/data/walk-joints.yaml");
  EXPECT_EQ(g.status, 2);
}

TEST(Decode, ExampleHexBackToTable) {
  SeqcRun r = seqc(kSource, "decode tests/golden/examples/walk.hex");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err, "");
  expect_golden(kCliGolden / "decode-walk.stdout", r.out);
}

TEST(Decode, ReadsStdin) {
  SeqcRun r = seqc(kSource, "decode -", (kGolden / "examples/walk.hex").string());
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out, slurp(kCliGolden / "decode-walk.stdout"));
}

TEST(Decode, FlagsInconsistentFrames) {
  // tests/cli/data/inconsistent.hex is written by hand: see the comments in it.
  SeqcRun r = seqc(kSource, "decode tests/cli/data/inconsistent.hex");
  EXPECT_EQ(r.status, 1);
  expect_golden(kCliGolden / "decode-inconsistent.stdout", r.out);
  expect_golden(kCliGolden / "decode-inconsistent.stderr", r.err);
}

TEST(Simulate, CsvAndDuration) {
  SeqcRun r = seqc(kSource, "simulate --step 100 examples/wave.yaml");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err, "seqc: examples/wave.yaml: 38 actions, 7.2 s\n");
  expect_golden(kCliGolden / "simulate-wave.csv", r.out);
}

TEST(Simulate, CarStateOverTime) {
  SeqcRun r = seqc(kSource, "simulate --step 250 examples/car-dance.yaml");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err.rfind("seqc: examples/car-dance.yaml: ", 0), 0u) << r.err;
  expect_golden(kCliGolden / "simulate-car-dance.csv", r.out);
}

// A show: one CSV per performer, each exactly what simulating that performer's file alone gives
// (the car's is the golden above), after a "# performer NAME (FILE)" line on stdout, or in
// OUT-NAME.csv with -o OUT.csv.
TEST(Simulate, AShowGivesOneCsvPerPerformer) {
  const SeqcRun walk = seqc(kSource, "simulate --step 250 examples/walk.yaml");
  ASSERT_EQ(walk.status, 0) << walk.err;
  const std::string car = slurp(kCliGolden / "simulate-car-dance.csv");
  SeqcRun r = seqc(kSource, "simulate --step 250 examples/duet.yaml");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out, "# performer arm (examples/walk.yaml)\n" + walk.out +
                       "# performer car (examples/car-dance.yaml)\n" + car);
  EXPECT_EQ(r.err.rfind("seqc: examples/walk.yaml (arm): 43 actions, 7.7 s\n"
                        "seqc: examples/car-dance.yaml (car): ",
                        0),
            0u)
      << r.err;

  const fs::path dir = fs::temp_directory_path() / "seqc-simulate-show";
  fs::remove_all(dir);
  fs::create_directories(dir);
  SeqcRun files =
      seqc(kSource, "simulate --step 250 examples/duet.yaml -o " + (dir / "duet.csv").string());
  EXPECT_EQ(files.status, 0) << files.err;
  EXPECT_EQ(files.out, "");
  EXPECT_EQ(slurp(dir / "duet-arm.csv"), walk.out);
  EXPECT_EQ(slurp(dir / "duet-car.csv"), car);
  EXPECT_FALSE(fs::exists(dir / "duet.csv"));
}

}  // namespace
