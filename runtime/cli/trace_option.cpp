#include "runtime/cli/trace_option.hpp"

#include <ostream>
#include <utility>

namespace seqc::cli {

void add_trace_option(CLI::App& cmd, std::string& path, const std::string& help) {
  cmd.add_option("--trace", path, help);
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
  transport_ = std::make_unique<upload::TraceTransport>(inner, clock, file_, board.dialect);
  return *transport_;
}

void Trace::wrap_in_place(std::unique_ptr<io::Transport>& slot, io::Clock& clock,
                          const boards::Board& board) {
  if (!file_.is_open()) return;
  untraced_ = std::move(slot);
  slot = std::make_unique<upload::TraceTransport>(*untraced_, clock, file_, board.dialect);
}

}  // namespace seqc::cli
