// One traced link (`--trace FILE` on every command that talks to a board): the file and the
// tracing transport in front of the board's. Every byte both ways goes to the file in the one
// trace format (upload::TraceTransport, docs/trace.md), whose header names the board's row of
// the dialect table, so `seqc decode` reads it in that dialect. The file is opened before the
// port, so a file that cannot be written sends nothing; it is written through io::OutputFile
// (the one safe writer: a temporary beside a regular file, renamed over it when the TraceFile
// ends, whatever the run's outcome; a device or FIFO written as the bytes come). Declared before
// what uses the traced transport, so it outlives it.
#pragma once

#include <memory>
#include <ostream>
#include <string>

#include "runtime/boards/board.hpp"
#include "runtime/io/clock.hpp"
#include "runtime/io/disk.hpp"
#include "runtime/io/transport.hpp"
#include "runtime/upload/trace_transport.hpp"

namespace seqc::boards {

class TraceFile {
 public:
  TraceFile();
  TraceFile(const TraceFile&) = delete;
  TraceFile& operator=(const TraceFile&) = delete;
  // Writes what is left and puts the file in place.
  ~TraceFile();
  // Opens `path` for writing (its old content stays until the trace ends); "" opens nothing and
  // succeeds. False when the file cannot be written.
  bool open(const std::string& path);
  // `inner` itself without a file, else `inner` wrapped so every byte is traced (once per
  // TraceFile: the header names the device and `board`'s dialect).
  io::Transport& wrap(io::Transport& inner, io::Clock& clock, const Board& board);
  // As wrap(), for a transport reached through `slot` (an opened port's): with a file, `slot`
  // becomes the tracing transport and this TraceFile keeps the one it held.
  void wrap_in_place(std::unique_ptr<io::Transport>& slot, io::Clock& clock, const Board& board);

 private:
  class Sink;  // the stream's buffer: flushed lines go to the file
  std::unique_ptr<io::OutputFile> file_;
  std::unique_ptr<Sink> sink_;
  std::ostream stream_;
  std::unique_ptr<io::Transport> untraced_;  // wrap_in_place's
  std::unique_ptr<upload::TraceTransport> transport_;
};

}  // namespace seqc::boards
