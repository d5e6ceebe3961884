#include "runtime/cli/trace_option.hpp"

#include <ostream>

namespace seqc::cli {

void add_trace_option(CLI::App& cmd, std::string& path) {
  cmd.add_option("--trace", path,
                 "Write every byte exchanged with the board, with times, to FILE "
                 "(docs/trace.md; `seqc decode FILE` reads it)");
}

ExitCode Trace::open(Context& ctx, const std::string& path) {
  if (path.empty()) return ExitCode::Ok;
  file_.open(path, std::ios::out | std::ios::trunc);
  if (!file_) {
    ctx.err << "seqc: error: --trace " << path << ": cannot write the file\n";
    return ExitCode::FileError;
  }
  return ExitCode::Ok;
}

io::Transport& Trace::wrap(io::Transport& inner, io::Clock& clock, const boards::Board& board) {
  if (!file_.is_open()) return inner;
  transport_ = std::make_unique<upload::TraceTransport>(inner, clock, file_, board.name);
  return *transport_;
}

}  // namespace seqc::cli
