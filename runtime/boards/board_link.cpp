#include "runtime/boards/board_link.hpp"

#include <utility>

namespace seqc::boards {

BoardLink open_link(const PortRequest& request, TraceFile& trace, io::Clock& clock,
                    const Hooks& hooks, const std::atomic<bool>* interrupted,
                    io::Duration timeout) {
  BoardLink link;
  link.request = request;
  OpenResult opened = open_port(request, clock, hooks);
  if (!opened.port) {
    link.failure = std::move(opened.failure);
    return link;
  }
  link.port = std::move(opened.port);
  link.transport = &trace.wrap(*link.port->transport, *link.port->clock, *request.board);
  link.line.emplace(Line{*link.transport, *link.port->clock, interrupted, timeout});
  return link;
}

}  // namespace seqc::boards
