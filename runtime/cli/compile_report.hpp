// Shared by the offline subcommands: compile one file, or load one that may be a show, and
// report on stderr the way every subcommand does (diagnostics, coloured when ctx.color, or
// "seqc: error: cannot read ..." for a file error). The path "-" reads a choreography from
// standard input; it is called <stdin> in diagnostics and its includes resolve from the current
// directory.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <CLI/CLI.hpp>

#include "base/diagnostics.hpp"
#include "compiler/compile.hpp"
#include "compiler/load.hpp"
#include "compiler/show.hpp"
#include "runtime/cli/clock_option.hpp"
#include "runtime/cli/context.hpp"
#include "runtime/cli/exit_codes.hpp"

namespace seqc::cli {

struct Compiled {
  compiler::CompileOutput output;
  ExitCode code = ExitCode::Ok;
  std::int32_t clock_ppm = 0;  // what the stored group was pre-scaled for
};

inline constexpr const char* kStdinName = "<stdin>";
inline constexpr const char* kStdoutName = "<stdout>";

// True, and said on stderr ("OPTION PATH is the same file as the input INPUT; nothing was
// written"), when `path` is the same file as one of `inputs` (io::same_file, links followed):
// the command must then write nothing and end with ExitCode::Usage.
bool refuse_input_as_output(Context& ctx, const std::string& option, const std::string& path,
                            const std::vector<std::string>& inputs);

// Writes `data` on ctx.out and flushes it; a failed stream (stdout closed or its disk full) is
// said as "<stdout>: cannot write" and is FileError.
ExitCode write_stdout(Context& ctx, std::string_view data);
// "seqc: error: <stdout>: cannot write[: strerror(error)]" (error 0: no reason known).
void say_stdout_failed(Context& ctx, int error);

// Writes what an offline subcommand made to `path` ("-" or "" = stdout, else through
// io::write_file_safely). An output that is one of `inputs` is refused before anything is
// written (Usage); a write that fails is FileError; either is said on stderr.
ExitCode write_output(Context& ctx, const std::string& path, const std::string& data,
                      const std::vector<std::string>& inputs = {},
                      const std::string& option = "-o");

// Loads a show file and prints its diagnostics and every performer's (for `seqc show`).
// code: Ok, FileError (the show file cannot be read) or InvalidInput.
compiler::ShowOutput load_show_and_report(Context& ctx, const std::string& path, bool strict,
                                          ExitCode& code);

// Whether to decode a `music:` song (through ctx.songs) and check the dance against it: the
// commands that check (check, compile, simulate, plot) do; the rest need only the program.
enum class SongCheck { Skip, Decode };

// `--port P` on a command that only compiles: P is checked as upload checks it (a bad one is a
// usage error) and only its link is used; nothing is opened.
void add_link_port_option(CLI::App& cmd, std::string& port);

// Compiles without printing anything (for --format json|sarif). clock_ppm: the board's clock
// error the stored group is pre-scaled for (compiler::CompileOptions::clock_ppm); chain: the
// dance may take consecutive groups (CompileOptions::chain; loads and views always may).
Compiled compile_quietly(Context& ctx, const std::string& path, bool strict,
                         SongCheck song = SongCheck::Skip, std::int32_t clock_ppm = 0,
                         bool over_hid = false, bool chain = false,
                         compiler::RobotStart start = {});
// Compiles and prints the diagnostics (or the file error) on ctx.err. With `clock`, the ppm to
// pre-scale for is resolved from --clock-ppm and --rig first (resolve_clock_ppm); when it cannot
// be, nothing is compiled and code is its status. over_hid: the port is USB HID
// (boards::port_over_hid), where every action must fit one report.
Compiled compile_and_report(Context& ctx, const std::string& path, bool strict,
                            SongCheck song = SongCheck::Skip,
                            const ClockScaleOptions* clock = nullptr, bool over_hid = false,
                            bool chain = false);

// Prints what compile_quietly found, as compile_and_report does.
void report_compile(Context& ctx, const Compiled& c, bool strict);

// A file given to a command that takes a choreography or a show (check, plot, simulate,
// preview), read once (compiler/load.hpp). code: Ok, FileError (the file given cannot be read)
// or InvalidInput (it, or for a show any performer, has errors).
struct Loaded {
  compiler::Loaded file;
  ExitCode code = ExitCode::Ok;
};

// Loads without printing anything: a choreography compiled as compile_quietly() compiles it
// (`song`, `clock_ppm`), a show's performers with `strict` alone. "-" is a choreography.
Loaded load_quietly(Context& ctx, const std::string& path, bool strict,
                    SongCheck song = SongCheck::Skip, std::int32_t clock_ppm = 0,
                    bool over_hid = false);
// Loads and prints the diagnostics (or the file error) on ctx.err: a show file's own, then
// every performer's.
Loaded load_and_report(Context& ctx, const std::string& path, bool strict,
                       SongCheck song = SongCheck::Skip, std::int32_t clock_ppm = 0,
                       bool over_hid = false);

}  // namespace seqc::cli
