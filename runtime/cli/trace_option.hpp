// `--trace` on every command that talks to a board (upload, play, show, group, servo, battery,
// offset, bus-info, teach): the one place the option is added and a transport wrapped. Every byte
// both ways goes to the file in the one trace format (upload::TraceTransport, docs/trace.md),
// whose header names the board's row of the dialect table, so `seqc decode` reads it in that
// dialect. The file is opened before the port, so a file that cannot be written sends nothing
// (exit 5).
#pragma once

#include <fstream>
#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "runtime/boards/board.hpp"
#include "runtime/cli/context.hpp"
#include "runtime/cli/exit_codes.hpp"
#include "runtime/io/clock.hpp"
#include "runtime/io/transport.hpp"
#include "runtime/upload/trace_transport.hpp"

namespace seqc::cli {

// The help of a command that traces one board to FILE.
inline constexpr const char* kTraceHelp =
    "Write every byte exchanged with the board, with times, to FILE "
    "(docs/trace.md; `seqc decode FILE` reads it)";

// Adds `--trace` storing into `path`, with `help` (a command whose file is not simply FILE, as
// `seqc show`'s per-performer files, words its own).
void add_trace_option(CLI::App& cmd, std::string& path, const std::string& help = kTraceHelp);

// One traced link: the file and the tracing transport in front of the board's. Declared before
// what uses the traced transport, so it outlives it.
class Trace {
 public:
  // Opens `path` for writing ("" opens nothing); on failure says so on ctx.err and returns
  // FileError.
  ExitCode open(Context& ctx, const std::string& path);
  // `inner` itself without a file, else `inner` wrapped so every byte is traced (once per
  // Trace: the header names the device and `board`'s dialect).
  io::Transport& wrap(io::Transport& inner, io::Clock& clock, const boards::Board& board);
  // As wrap(), for a transport reached through `slot` (an opened port's): with a file, `slot`
  // becomes the tracing transport and this Trace keeps the one it held.
  void wrap_in_place(std::unique_ptr<io::Transport>& slot, io::Clock& clock,
                     const boards::Board& board);

 private:
  std::ofstream file_;
  std::unique_ptr<io::Transport> untraced_;  // wrap_in_place's
  std::unique_ptr<upload::TraceTransport> transport_;
};

}  // namespace seqc::cli
