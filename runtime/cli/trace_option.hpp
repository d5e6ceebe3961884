// `--trace FILE` on every command that talks to a board (upload, play, show, group, servo,
// battery, offset, bus-info, teach): every byte both ways written to FILE in the one trace format
// (upload::TraceTransport, docs/trace.md), which `seqc decode` reads. The file is opened before
// the port, so a file that cannot be written sends nothing (exit 5).
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

void add_trace_option(CLI::App& cmd, std::string& path);

class Trace {
 public:
  // Opens `path` for writing ("" opens nothing); on failure says so on ctx.err and returns
  // FileError.
  ExitCode open(Context& ctx, const std::string& path);
  // `inner` itself without a file, else `inner` wrapped so every byte is traced (once per
  // Trace: the header names the device and `board`'s dialect).
  io::Transport& wrap(io::Transport& inner, io::Clock& clock, const boards::Board& board);

 private:
  std::ofstream file_;
  std::unique_ptr<upload::TraceTransport> transport_;
};

}  // namespace seqc::cli
