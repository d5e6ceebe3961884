// The exit status of every subcommand, as docs/cli.md and docs/commands.md promise it: 0 ok,
// 1 invalid input, 2 usage error, 3 port unavailable, 4 device failure, 5 file error. Each
// expected status below is a number copied from those documents, never the program's enum.
// Everything runs the real binary; devices are the built-in emulators (`emu:xarm`, and
// `emu:xarm?drop=1`, a controller that never answers, for device failures) and a port path that
// cannot exist, so no hardware is needed.
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/cli/seqc_run.hpp"

namespace seqc::testing {
namespace {

// Written so that `{tmp}` in a case's arguments is that case's own scratch folder.
constexpr const char* kValid = "tests/data/walk-joints.yaml";
constexpr const char* kInvalid = "tests/golden/bad-unknown-pose.yaml";
constexpr const char* kMissing = "no-such-file.yaml";
constexpr const char* kSilent = "'emu:xarm?drop=1'";  // a controller that answers nothing
constexpr const char* kNoPort = "/dev/seqc-no-such-port";

// ---------------------------------------------------------------------------------------------
// check --format text|json|sarif: "with the same exit status" (docs/cli.md) on a valid file, an
// invalid one and one that cannot be read.

struct FormatCase {
  const char* format;
  const char* file;
  int status;
};

// Named in test listings by what they are rather than by their bytes.
void PrintTo(const FormatCase& c, std::ostream* os) {
  *os << c.format << ' ' << c.file << " -> " << c.status;
}

class CheckFormatStatus : public ::testing::TestWithParam<FormatCase> {};

TEST_P(CheckFormatStatus, IsTheDocumentedOne) {
  const FormatCase& c = GetParam();
  const SeqcRun r = seqc(kSource, std::string("check --format ") + c.format + " " + c.file);
  EXPECT_EQ(r.status, c.status) << "stdout:\n" << r.out << "stderr:\n" << r.err;
  if (std::string(c.format) != "text") {
    EXPECT_NE(r.out, "") << "json and sarif always print a document";
    EXPECT_EQ(r.err, "") << "json and sarif print nothing on stderr";
  }
}

INSTANTIATE_TEST_SUITE_P(
    Matrix, CheckFormatStatus,
    ::testing::Values(FormatCase{"text", kValid, 0}, FormatCase{"text", kInvalid, 1},
                      FormatCase{"text", kMissing, 5}, FormatCase{"json", kValid, 0},
                      FormatCase{"json", kInvalid, 1}, FormatCase{"json", kMissing, 5},
                      FormatCase{"sarif", kValid, 0}, FormatCase{"sarif", kInvalid, 1},
                      FormatCase{"sarif", kMissing, 5}),
    [](const ::testing::TestParamInfo<FormatCase>& param_info) {
      const std::string file = param_info.param.file;
      const char* what = file == kValid ? "valid" : file == kInvalid ? "invalid" : "unreadable";
      return std::string(param_info.param.format) + "_" + what;
    });

// ---------------------------------------------------------------------------------------------
// Every subcommand that `seqc --help` lists: a documented failure, and success where cheap.

struct StatusCase {
  const char* name;
  std::string args;  // after `seqc`; {tmp} is the case's scratch folder
  int status;
  std::function<void(const fs::path& tmp)> setup = nullptr;
};

void PrintTo(const StatusCase& c, std::ostream* os) {
  *os << "seqc " << c.args << " -> " << c.status;
}

void write(const fs::path& p, const std::string& text) { std::ofstream(p) << text; }

// A show file in `tmp` with one servo-controller performer (walk.yaml) on `port`.
std::function<void(const fs::path&)> show_on(std::string port) {
  return [port](const fs::path& tmp) {
    write(tmp / "show.yaml", "show: one\nperformers:\n  arm: {file: " +
                                 (kSource / kValid).string() + ", port: " + port + ", group: 0}\n");
  };
}

void copy_walk(const fs::path& tmp) {
  fs::copy_file(kSource / kValid, tmp / "walk.yaml", fs::copy_options::overwrite_existing);
}

class SubcommandStatus : public ::testing::TestWithParam<StatusCase> {};

TEST_P(SubcommandStatus, IsTheDocumentedOne) {
  const StatusCase& c = GetParam();
  const fs::path tmp = fs::path(SEQC_BINARY_DIR) / "tests/cli/exit-status" / c.name;
  fs::remove_all(tmp);
  fs::create_directories(tmp);
  if (c.setup) c.setup(tmp);
  std::string args = c.args;
  for (std::size_t at; (at = args.find("{tmp}")) != std::string::npos;) {
    args.replace(at, 5, tmp.string());
  }
  const SeqcRun r = seqc(kSource, args);
  EXPECT_EQ(r.status, c.status) << "seqc " << args << "\nstderr:\n" << r.err;
  if (c.status != 0) {
    // A failure says why on stderr (`seqc: error: ...`, a diagnostic, or decode's warning).
    EXPECT_NE(r.err, "") << "seqc " << args;
  }
  fs::remove_all(tmp);
}

const std::string valid = kValid;
const std::string invalid = kInvalid;
const std::string missing = kMissing;
const std::string silent = kSilent;
const std::string no_port = kNoPort;

INSTANTIATE_TEST_SUITE_P(
    Table, SubcommandStatus,
    ::testing::Values(
        // Global: a mistyped subcommand is a usage error.
        StatusCase{"unknown_subcommand", "chekc " + valid, 2},
        StatusCase{"version", "--version", 0},
        // check: 0 every file valid, 1 any has errors, 5 any could not be read.
        StatusCase{"check_ok", "check " + valid, 0},
        StatusCase{"check_invalid", "check " + valid + " " + invalid, 1},
        StatusCase{"check_unreadable", "check " + valid + " " + invalid + " " + missing, 5},
        StatusCase{"check_usage", "check --format xml " + valid, 2},
        // compile: 1 on errors, 5 if FILE cannot be read or OUT cannot be written.
        StatusCase{"compile_ok", "compile " + valid + " -o {tmp}/walk.hex", 0},
        StatusCase{"compile_invalid", "compile " + invalid, 1},
        StatusCase{"compile_unreadable", "compile " + missing, 5},
        StatusCase{"compile_unwritable", "compile " + valid + " -o {tmp}/no/such/dir/x.hex", 5},
        StatusCase{"compile_usage", "compile " + valid + " --emit bogus", 2},
        // decode: 0 if there is no inconsistency, 1 otherwise.
        StatusCase{"decode_ok", "decode tests/golden/examples/walk.hex", 0},
        StatusCase{"decode_inconsistent", "decode tests/cli/data/inconsistent.hex", 1},
        StatusCase{"decode_unreadable", "decode no-such-file.hex", 5},
        StatusCase{"decode_usage", "decode --from bogus tests/golden/examples/walk.hex", 2},
        // simulate
        StatusCase{"simulate_ok", "simulate " + valid, 0},
        StatusCase{"simulate_invalid", "simulate " + invalid, 1},
        StatusCase{"simulate_unreadable", "simulate " + missing, 5},
        StatusCase{"simulate_usage", "simulate " + valid + " --step 0", 2},
        // plot
        StatusCase{"plot_ok", "plot " + valid + " -o {tmp}/walk.svg", 0},
        StatusCase{"plot_invalid", "plot " + invalid, 1},
        StatusCase{"plot_unreadable", "plot " + missing, 5},
        StatusCase{"plot_unwritable", "plot " + valid + " -o {tmp}/no/such/dir/x.svg", 5},
        StatusCase{"plot_usage", "plot " + valid + " --from 4s --to 2s", 2},
        // emulate serves until Ctrl-C (exit 0, tested in emulate_cli_test); a bad device or
        // fault list is a usage error before any terminal is opened.
        StatusCase{"emulate_usage_device", "emulate bogus", 2},
        StatusCase{"emulate_usage_faults", "emulate xarm --faults nonsense=1", 2},
        // ports: --json and --names exit 0, found or not.
        StatusCase{"ports_json", "ports --json", 0}, StatusCase{"ports_names", "ports --names", 0},
        StatusCase{"ports_usage", "ports --json --names", 2},
        // play
        StatusCase{"play_ok", "play " + valid + " --port emu:xarm --allow-late", 0},
        StatusCase{"play_invalid", "play " + invalid + " --port emu:xarm", 1},
        // A schedule the 9600-baud link cannot keep is refused (docs/commands.md, Live play).
        StatusCase{"play_too_late", "play tests/cli/data/too-dense.yaml --port emu:xarm", 1},
        StatusCase{"play_unreadable", "play " + missing + " --port emu:xarm", 5},
        StatusCase{"play_no_port", "play " + valid + " --port " + no_port, 3},
        StatusCase{"play_no_answer", "play " + valid + " --port " + silent + " --allow-late", 4},
        StatusCase{"play_usage", "play " + valid + " --port emu:xarm --times 0", 2},
        // upload: an invalid file never opens the port.
        StatusCase{"upload_ok", "upload " + valid + " --port emu:xarm", 0},
        StatusCase{"upload_invalid", "upload " + invalid + " --port " + no_port, 1},
        StatusCase{"upload_unreadable", "upload " + missing + " --port emu:xarm", 5},
        StatusCase{"upload_no_port", "upload " + valid + " --port " + no_port, 3},
        StatusCase{"upload_no_answer", "upload " + valid + " --port " + silent, 4},
        StatusCase{"upload_usage", "upload " + valid + " --group 255 --port emu:xarm", 2},
        // The servo controller commands (docs/commands.md): 0, 1 and 2 (nothing is sent), 3, 4.
        StatusCase{"group_ok", "group run 3 --port emu:xarm", 0},
        StatusCase{"group_usage", "group run 300 --port emu:xarm", 2},
        StatusCase{"group_no_port", "group stop --port " + no_port, 3},
        StatusCase{"group_no_answer", "group stop --port " + silent, 4},
        StatusCase{"battery_ok", "battery --port emu:xarm", 0},
        StatusCase{"battery_usage", "battery --port emu:xarm --timeout nonsense", 2},
        StatusCase{"battery_no_port", "battery --port " + no_port, 3},
        StatusCase{"battery_no_answer", "battery --port " + silent, 4},
        StatusCase{"servo_ok", "servo read 1 --port emu:xarm", 0},
        StatusCase{"servo_usage", "servo move 1:500 --port emu:xarm", 2},
        // A position outside every servo controller's range (0..2500) is invalid input.
        StatusCase{"servo_out_of_range", "servo move 1=5000 --port emu:xarm", 1},
        StatusCase{"servo_no_port", "servo read 1 --port " + no_port, 3},
        StatusCase{"servo_no_answer", "servo read 1 --port " + silent, 4},
        StatusCase{"offset_ok", "offset read 1 --port emu:xarm", 0},
        StatusCase{"offset_usage", "offset adjust 1 -200 --port emu:xarm", 2},
        StatusCase{"offset_no_port", "offset read 1 --port " + no_port, 3},
        StatusCase{"offset_no_answer", "offset read 1 --port " + silent, 4},
        StatusCase{"bus_info_ok", "bus-info read --port emu:xarm", 0},
        StatusCase{"bus_info_usage", "bus-info write --position-max 900 --port emu:xarm", 2},
        StatusCase{"bus_info_no_port", "bus-info read --port " + no_port, 3},
        StatusCase{"bus_info_no_answer", "bus-info read --port " + silent, 4},
        // import: 1 for a file that is not a .d6a, 5 for one that cannot be read.
        StatusCase{
            "import_ok", "import {tmp}/walk.d6a -o {tmp}/walk.yaml", 0,
            [](const fs::path& tmp) {
              ASSERT_EQ(
                  seqc(kSource, "export " + valid + " -o " + (tmp / "walk.d6a").string()).status,
                  0);
            }},
        StatusCase{"import_invalid", "import " + valid, 1},
        StatusCase{"import_unreadable", "import no-such-file.d6a", 5},
        StatusCase{"import_usage", "import " + valid + " --robot", 2},
        // export
        StatusCase{"export_ok", "export " + valid + " -o {tmp}/walk.d6a", 0},
        StatusCase{"export_invalid", "export " + invalid + " -o {tmp}/bad.d6a", 1},
        StatusCase{"export_unreadable", "export " + missing + " -o {tmp}/x.d6a", 5},
        StatusCase{"export_unwritable", "export " + valid + " -o {tmp}/no/such/dir/x.d6a", 5},
        StatusCase{"export_usage", "export " + valid + " --group 255", 2},
        // teach reads Enter/q from stdin (here empty: no pose is added).
        StatusCase{"teach_ok", "teach {tmp}/walk.yaml --port emu:xarm", 0, copy_walk},
        StatusCase{"teach_unreadable", "teach {tmp}/none.yaml --port emu:xarm", 5},
        StatusCase{"teach_no_port", "teach {tmp}/walk.yaml --port " + no_port, 3, copy_walk},
        StatusCase{"teach_no_answer", "teach {tmp}/walk.yaml --port " + silent, 4, copy_walk},
        StatusCase{"teach_usage", "teach {tmp}/walk.yaml --port emu:xarm --timeout x", 2,
                   copy_walk},
        // show: if any upload fails nothing starts.
        StatusCase{"show_ok", "show {tmp}/show.yaml", 0, show_on("emu:xarm")},
        StatusCase{"show_invalid", "show " + invalid, 1},
        StatusCase{"show_unreadable", "show " + missing, 5},
        StatusCase{"show_no_port", "show {tmp}/show.yaml", 3, show_on(no_port)},
        StatusCase{"show_no_answer", "show {tmp}/show.yaml", 4, show_on("\"emu:xarm?drop=1\"")},
        StatusCase{"show_usage", "show", 2},
        // help
        StatusCase{"help_ok", "help group run", 0}, StatusCase{"help_usage", "help nosuch", 2}),
    [](const ::testing::TestParamInfo<StatusCase>& param_info) {
      return std::string(param_info.param.name);
    });

}  // namespace
}  // namespace seqc::testing
