// `--trace` on every command that talks to a board (upload, play, show, group, servo, battery,
// offset, bus-info, teach): the one place the option is added, and the words when its file
// cannot be written (exit 5, nothing sent). The traced link itself is boards::TraceFile
// (runtime/boards/trace_file.hpp).
#pragma once

#include <string>

#include <CLI/CLI.hpp>

#include "runtime/boards/trace_file.hpp"
#include "runtime/cli/context.hpp"
#include "runtime/cli/exit_codes.hpp"

namespace seqc::cli {

// The help of a command that traces one board to FILE.
inline constexpr const char* kTraceHelp =
    "Write every byte exchanged with the board, with times, to FILE "
    "(docs/trace.md; `seqc decode FILE` reads it)";

// Adds `--trace` storing into `path`, with `help` (a command whose file is not simply FILE, as
// `seqc show`'s per-performer files, words its own).
void add_trace_option(CLI::App& cmd, std::string& path, const std::string& help = kTraceHelp);

// Opens `trace` on `path` ("" opens nothing); on failure says so on ctx.err and returns
// FileError.
ExitCode open_trace(Context& ctx, boards::TraceFile& trace, const std::string& path);
// Says that the trace file `path` cannot be written; returns FileError.
ExitCode trace_unwritable(Context& ctx, const std::string& path);

}  // namespace seqc::cli
