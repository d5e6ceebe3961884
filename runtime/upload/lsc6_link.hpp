// Request/answer over a byte link to an LSC-6 board (docs/protocol/lsc-6.md). The board's only
// answers are 55 55 02 <cmd>; none says which request it answers, so callers pair them by
// order and by time. The link sends one request, then reads answers until one is taken or the
// deadline passes; GroupFinished notices that arrive meanwhile are kept, anything else that is
// not an LSC-6 answer is skipped and counted.
//
// As ControllerLink: waits happen in slices of at most 100 ms on the injected clock, the
// interrupt flag is polled between slices, and a device that goes away is HangUp, never a
// timeout. The link never sleeps or reads the wall clock itself.
#pragma once

#include <atomic>
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "runtime/io/clock.hpp"
#include "runtime/io/transport.hpp"
#include "protocol/lsc6_messages.hpp"
#include "protocol/lsc_stream.hpp"
#include "runtime/upload/controller_link.hpp"

namespace seqc::upload {

struct Lsc6Wait {
  WaitStatus status = WaitStatus::Timeout;
  lsc6::Reply reply;
  std::string message;
  bool ok() const { return status == WaitStatus::Matched; }
};

class Lsc6Link {
 public:
  Lsc6Link(io::Transport& transport, io::Clock& clock,
           const std::atomic<bool>* interrupted = nullptr);

  Status send(const lsc6::Request& request);
  Status send_bytes(ByteView bytes);
  // Reads until `take` accepts an answer or `deadline` passes. Answers not taken are counted in
  // skipped(); GroupFinished notices are also kept in finished_notices().
  Lsc6Wait wait_for(const std::function<bool(const lsc6::Reply&)>& take, io::TimePoint deadline);
  // The answers that have already arrived, without waiting (HangUp/Error in `status`).
  std::vector<lsc6::Reply> drain(WaitStatus& status);
  void discard_input();

  bool interrupted() const { return interrupted_ != nullptr && interrupted_->load(); }
  io::Clock& clock() { return clock_; }
  io::Transport& transport() { return transport_; }
  double seconds_per_byte() const { return transport_.seconds_per_byte(); }
  LinkStats stats() const;
  std::size_t finished_notices() const { return finished_; }
  std::size_t skipped() const { return skipped_; }
  // Replies of the xArm dialect to GetBatteryVoltage (55 55 04 0f lo hi) among the frames read:
  // a board of that dialect is on the line.
  std::size_t other_dialect_replies() const { return other_dialect_; }

 private:
  std::optional<lsc6::Reply> next_answer();
  io::ReadResult read_some(io::TimePoint deadline);

  io::Transport& transport_;
  io::Clock& clock_;
  const std::atomic<bool>* interrupted_;
  lsc::FrameDecoder decoder_;
  LinkStats stats_;
  std::size_t finished_ = 0;
  std::size_t skipped_ = 0;
  std::size_t other_dialect_ = 0;
};

}  // namespace seqc::upload
