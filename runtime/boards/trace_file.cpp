#include "runtime/boards/trace_file.hpp"

#include <utility>

namespace seqc::boards {

bool TraceFile::open(const std::string& path) {
  if (path.empty()) return true;
  file_.open(path, std::ios::out | std::ios::trunc);
  return static_cast<bool>(file_);
}

io::Transport& TraceFile::wrap(io::Transport& inner, io::Clock& clock, const Board& board) {
  if (!file_.is_open()) return inner;
  transport_ = std::make_unique<upload::TraceTransport>(inner, clock, file_, board.dialect);
  return *transport_;
}

void TraceFile::wrap_in_place(std::unique_ptr<io::Transport>& slot, io::Clock& clock,
                              const Board& board) {
  if (!file_.is_open()) return;
  untraced_ = std::move(slot);
  slot = std::make_unique<upload::TraceTransport>(*untraced_, clock, file_, board.dialect);
}

}  // namespace seqc::boards
