#include "runtime/boards/trace_file.hpp"

#include <streambuf>
#include <utility>

namespace seqc::boards {

// Collects what the trace writes and hands it to the file at each flush (the tracing transport
// flushes after every line), so a device or FIFO sees each line as it happens.
class TraceFile::Sink final : public std::streambuf {
 public:
  explicit Sink(io::OutputFile& file) : file_(file) {}

 protected:
  int_type overflow(int_type c) override {
    if (!traits_type::eq_int_type(c, traits_type::eof())) pending_ += traits_type::to_char_type(c);
    return traits_type::not_eof(c);
  }
  std::streamsize xsputn(const char* s, std::streamsize n) override {
    pending_.append(s, static_cast<std::size_t>(n));
    return n;
  }
  int sync() override {
    const bool written = pending_.empty() || file_.write(pending_).ok();
    pending_.clear();
    return written ? 0 : -1;
  }

 private:
  io::OutputFile& file_;
  std::string pending_;
};

TraceFile::TraceFile() : stream_(nullptr) {}

TraceFile::~TraceFile() {
  if (!file_) return;
  stream_.flush();
  (void)file_->finish();  // a trace that cannot be put in place has nowhere to say so
}

bool TraceFile::open(const std::string& path) {
  if (path.empty()) return true;
  auto file = io::OutputFile::open(path);
  if (!file) return false;
  file_ = std::move(*file);
  sink_ = std::make_unique<Sink>(*file_);
  stream_.rdbuf(sink_.get());
  return true;
}

io::Transport& TraceFile::wrap(io::Transport& inner, io::Clock& clock, const Board& board) {
  if (!file_) return inner;
  transport_ = std::make_unique<upload::TraceTransport>(inner, clock, stream_, board.dialect);
  return *transport_;
}

void TraceFile::wrap_in_place(std::unique_ptr<io::Transport>& slot, io::Clock& clock,
                              const Board& board) {
  if (!file_) return;
  untraced_ = std::move(slot);
  slot = std::make_unique<upload::TraceTransport>(*untraced_, clock, stream_, board.dialect);
}

}  // namespace seqc::boards
