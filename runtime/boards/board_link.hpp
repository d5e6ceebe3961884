// A device command's line to its board: the port a request names opened (ports.hpp), its
// transport wrapped by the command's trace (trace_file.hpp, opened by the caller before, so an
// unwritable trace opens no port) and the line over them that the board's rows take. Returns
// data only: a port that does not open leaves `port` unset and `failure` saying why.
#pragma once

#include <atomic>
#include <chrono>
#include <optional>

#include "runtime/boards/board.hpp"
#include "runtime/boards/hooks.hpp"
#include "runtime/boards/ports.hpp"
#include "runtime/boards/trace_file.hpp"
#include "runtime/io/clock.hpp"

namespace seqc::boards {

// Holds the port, so it must outlive every use of `line`; `trace` must outlive both.
struct BoardLink {
  PortRequest request;
  std::optional<OpenedPort> port;
  PortFailure failure;                 // when `port` is unset
  io::Transport* transport = nullptr;  // the port's transport, traced
  std::optional<Line> line;            // over `transport` and the port's clock
};

// Opens request's port and wraps its transport with `trace` for `request.board`'s dialect
// (which must be set). `timeout` is the line's wait per awaited reply.
BoardLink open_link(const PortRequest& request, TraceFile& trace, io::Clock& clock,
                    const Hooks& hooks, const std::atomic<bool>* interrupted,
                    io::Duration timeout = std::chrono::seconds(1));

}  // namespace seqc::boards
