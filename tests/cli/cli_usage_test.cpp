// The command line as a person meets it, through the real binary: "did you mean" for
// mistyped subcommands and options, `seqc help`, --version, global -q/-v, colour, `-` for
// stdin and stdout, and check's machine formats.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "tests/cli/seqc_run.hpp"

namespace {

using seqc::testing::expect_golden;
using seqc::testing::kCliGolden;
using seqc::testing::kSource;
using seqc::testing::seqc;
using seqc::testing::SeqcRun;

TEST(Usage, MistypedSubcommandSuggestsTheClosest) {
  const SeqcRun r = seqc(kSource, "chekc tests/data/walk-joints.yaml");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.out, "");
  expect_golden(kCliGolden / "usage-unknown-command.stderr", r.err);
}

TEST(Usage, MistypedOptionSuggestsTheClosestOfThatSubcommand) {
  const SeqcRun r = seqc(kSource, "check --strct tests/data/walk-joints.yaml");
  EXPECT_EQ(r.status, 2);
  expect_golden(kCliGolden / "usage-unknown-option.stderr", r.err);
  // A nested subcommand, and a global option after the subcommand.
  EXPECT_EQ(seqc(kSource, "group rn 3").err,
            "seqc: error: unknown group command 'rn'; did you mean 'run'?\n"
            "seqc: run 'seqc help' for the list of commands and options\n");
  EXPECT_EQ(seqc(kSource, "upload tests/data/walk-joints.yaml --quite").err,
            "seqc: error: unknown option '--quite' for 'seqc upload'; did you mean '--quiet'?\n"
            "seqc: run 'seqc help' for the list of commands and options\n");
  // Nothing close: no suggestion.
  EXPECT_EQ(seqc(kSource, "xyzzy").err,
            "seqc: error: unknown command 'xyzzy'\n"
            "seqc: run 'seqc help' for the list of commands and options\n");
  // A negative number is a value, not an option.
  EXPECT_EQ(seqc(kSource, "offset adjust 1 -20 --port emu:xarm").status, 0);
}

TEST(Usage, AMissingArgumentPointsAtTheRightHelp) {
  EXPECT_EQ(seqc(kSource, "").err,
            "seqc: error: A subcommand is required\n"
            "seqc: run 'seqc help' for the list of commands and options\n");
  const SeqcRun r = seqc(kSource, "group run");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err,
            "seqc: error: GROUP is required\n"
            "seqc: run 'seqc help group run' for its options\n");
}

TEST(Usage, HelpSubcommandPrintsTheSameTextAsDashDashHelp) {
  EXPECT_EQ(seqc(kSource, "help").out, seqc(kSource, "--help").out);
  EXPECT_EQ(seqc(kSource, "help check").out, seqc(kSource, "check --help").out);
  const SeqcRun nested = seqc(kSource, "help group run");
  EXPECT_EQ(nested.status, 0);
  EXPECT_EQ(nested.out, seqc(kSource, "group run --help").out);
  EXPECT_NE(nested.out.find("GroupRun"), std::string::npos);
  const SeqcRun unknown = seqc(kSource, "help uplaod");
  EXPECT_EQ(unknown.status, 2);
  EXPECT_EQ(unknown.err,
            "seqc: error: no help for 'uplaod': unknown command; did you mean 'upload'?\n");
}

TEST(Usage, VersionComesFromTheProjectVersion) {
  const SeqcRun r = seqc(kSource, "--version");
  EXPECT_EQ(r.status, 0);
  EXPECT_EQ(r.out, "seqc " SEQC_PROJECT_VERSION "\n");
}

TEST(Usage, QuietLeavesOnlyDataAndVerboseAddsDetail) {
  const SeqcRun normal = seqc(kSource, "upload tests/data/walk-joints.yaml --port emu:xarm");
  ASSERT_EQ(normal.status, 0) << normal.err;
  EXPECT_NE(normal.err.find("seqc: the controller acknowledged 27 actions"), std::string::npos);
  EXPECT_EQ(normal.err.find("upload: 29 actions into group 0"), std::string::npos);

  const SeqcRun quiet = seqc(kSource, "-q upload tests/data/walk-joints.yaml --port emu:xarm");
  EXPECT_EQ(quiet.status, 0);
  EXPECT_EQ(quiet.out, "");
  EXPECT_EQ(quiet.err, "");
  EXPECT_EQ(seqc(kSource, "upload tests/data/walk-joints.yaml --port emu:xarm --quiet").err, "");

  const SeqcRun verbose = seqc(kSource, "upload tests/data/walk-joints.yaml --port emu:xarm -v");
  EXPECT_NE(verbose.err.find("upload: 27 actions into group 0 on emu:xarm"), std::string::npos)
      << verbose.err;
  // Errors are never quiet.
  const SeqcRun bad = seqc(kSource, "-q check tests/golden/bad-unknown-pose.yaml");
  EXPECT_EQ(bad.status, 1);
  EXPECT_NE(bad.err.find("error: unknown pose 'raech'"), std::string::npos);
}

TEST(Usage, ColorOnlyWhenAskedOrOnATerminal) {
  const std::string bad = "check tests/golden/bad-unknown-pose.yaml";
  const SeqcRun plain = seqc(kSource, bad);
  EXPECT_EQ(plain.err.find('\033'), std::string::npos);  // stderr is a file here: auto = off
  const SeqcRun always = seqc(kSource, "--color=always " + bad);
  EXPECT_NE(always.err.find("\033[31merror: "), std::string::npos) << always.err;
  EXPECT_NE(always.err.find("\033[32m^"), std::string::npos);
  // The coloured text is the plain text plus escape sequences, nothing else.
  std::string stripped;
  for (std::size_t i = 0; i < always.err.size(); ++i) {
    if (always.err[i] == '\033') {
      i = always.err.find('m', i);
      continue;
    }
    stripped += always.err[i];
  }
  EXPECT_EQ(stripped, plain.err);
  EXPECT_EQ(seqc(kSource, "--color=never " + bad).err, plain.err);
  EXPECT_EQ(seqc(kSource, "--color=sometimes " + bad).status, 2);
}

TEST(Usage, DashIsStdinForFilesAndStdoutForOutput) {
  const SeqcRun in = seqc(kSource, "check -", (kSource / "tests/data/walk-joints.yaml").string());
  EXPECT_EQ(in.status, 0) << in.err;
  EXPECT_EQ(in.out.rfind("<stdin>: 27/1020 actions", 0), 0u) << in.out;
  const SeqcRun bad =
      seqc(kSource, "check -", (kSource / "tests/golden/bad-unknown-pose.yaml").string());
  EXPECT_EQ(bad.status, 1);
  EXPECT_EQ(bad.err.rfind("<stdin>:5:11: error: unknown pose 'raech'", 0), 0u) << bad.err;

  const SeqcRun to_stdout = seqc(kSource, "compile tests/data/walk-joints.yaml -o -");
  EXPECT_EQ(to_stdout.status, 0);
  EXPECT_EQ(to_stdout.out, seqc(kSource, "compile tests/data/walk-joints.yaml").out);
  EXPECT_EQ(seqc(kSource, "simulate examples/wave.yaml -o -").out,
            seqc(kSource, "simulate examples/wave.yaml").out);
  EXPECT_EQ(
      seqc(kSource, "compile - --emit listing", (kSource / "tests/data/walk-joints.yaml").string()).status,
      0);
}

TEST(Usage, DryRunFramesDecodeBack) {
  // Through a real pipe, as the documentation shows it.
  const std::string cmd = "cd '" + kSource.string() +
                          "' && '" SEQC_BIN "' compile --dry-run tests/data/walk-joints.yaml | '" SEQC_BIN
                          "' decode -";
  FILE* p = popen(cmd.c_str(), "r");
  ASSERT_NE(p, nullptr);
  std::string out;
  char buf[512];
  while (fgets(buf, sizeof buf, p) != nullptr) out += buf;
  EXPECT_EQ(WEXITSTATUS(pclose(p)), 0);
  EXPECT_NE(out.find("GroupStop"), std::string::npos) << out;
  EXPECT_NE(out.find("# 35 frame(s), 27 action(s), 8 s total, 0 issue(s)"), std::string::npos)
      << out;
}

TEST(CheckFormats, JsonGolden) {
  const SeqcRun r = seqc(kSource,
                         "check --format json tests/golden/bad-error-in-include.yaml "
                         "tests/golden/bad-duplicate-key.yaml tests/data/walk-joints.yaml");
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.err, "");
  expect_golden(kCliGolden / "check-format.json", r.out);
  const SeqcRun clean = seqc(kSource, "check --format json tests/data/walk-joints.yaml");
  EXPECT_EQ(clean.status, 0);
  EXPECT_EQ(clean.out, "[]\n");
}

TEST(CheckFormats, UnreadableFileIsADiagnosticOfThatFile) {
  const SeqcRun r = seqc(kSource, "check --format json no-such-file.yaml");
  EXPECT_EQ(r.status, 5);
  EXPECT_EQ(r.out.rfind("[\n  {\"file\": \"no-such-file.yaml\", \"severity\": \"error\", "
                        "\"rule\": \"file-error\"",
                        0),
            0u)
      << r.out;
}

}  // namespace

namespace {

TEST(Plot, SmallProgramGolden) {
  // Every kind of mark: bar grid, a section and an `at:` cue, a curve and its actions, a narrowed
  // limit, and the speed warning with its message as the marker's <title>.
  const SeqcRun r = seqc(kSource, "plot tests/plot/small.yaml");
  EXPECT_EQ(r.status, 0) << r.err;
  expect_golden(seqc::testing::kGolden / "plot/small.svg", r.out);
  EXPECT_NE(r.out.find("<title>warning: 600 in 200ms is 3000/s, above base's 833/s</title>"),
            std::string::npos);
  EXPECT_EQ(r.out.find("<script"), std::string::npos);
  EXPECT_EQ(r.out.find("href"), std::string::npos);  // nothing external
}

TEST(Plot, TipPanelsShowTheLineAndTheMotion) {
  const SeqcRun r = seqc(kSource, "plot tests/plot/tip-line.yaml");
  EXPECT_EQ(r.status, 0) << r.err;
  expect_golden(seqc::testing::kGolden / "plot/tip-line.svg", r.out);
  EXPECT_NE(r.out.find("<title>from above</title>"), std::string::npos);
  EXPECT_NE(r.out.find("<title>from the side</title>"), std::string::npos);
  EXPECT_NE(r.out.find(">x (mm)</text>"), std::string::npos);
  EXPECT_NE(r.out.find(">z (mm)</text>"), std::string::npos);
  // One dashed line per panel for the one `path: line` move.
  const std::size_t panels = r.out.find("class=\"tip-view\"");
  ASSERT_NE(panels, std::string::npos);
  std::size_t dashed = 0;
  for (std::size_t at = r.out.find("stroke-dasharray=\"5 3\"", panels); at != std::string::npos;
       at = r.out.find("stroke-dasharray=\"5 3\"", at + 1)) {
    ++dashed;
  }
  EXPECT_EQ(dashed, 2u);
  // A file that never places the tip in millimetres has no panels.
  const SeqcRun small = seqc(kSource, "plot tests/plot/small.yaml");
  EXPECT_EQ(small.out.find("tip-view"), std::string::npos);
}

TEST(Plot, TheReadmePictureIsCurrent) {
  const SeqcRun r = seqc(kSource, "plot examples/waltz.yaml");
  EXPECT_EQ(r.status, 0) << r.err;
  expect_golden(kSource / "docs/images/waltz.svg", r.out);
}

TEST(Plot, WindowAndErrors) {
  const SeqcRun window = seqc(kSource, "plot tests/data/walk-joints.yaml --from 2s --to 4s");
  EXPECT_EQ(window.status, 0);
  EXPECT_NE(window.out.find(">2 s</text>"), std::string::npos);
  EXPECT_NE(window.out.find(">4 s</text>"), std::string::npos);
  EXPECT_EQ(window.out.find(">6 s</text>"), std::string::npos);
  EXPECT_EQ(seqc(kSource, "plot tests/data/walk-joints.yaml --from 4s --to 2s").status, 2);
  EXPECT_EQ(seqc(kSource, "plot tests/data/walk-joints.yaml --from 2b").err,
            "seqc: error: --from 2b: give a time in ms or s, e.g. 1.5s\n");
  EXPECT_EQ(seqc(kSource, "plot tests/golden/bad-unknown-pose.yaml").status, 1);
}

}  // namespace
