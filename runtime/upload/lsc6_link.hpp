// Request/answer over a byte link to an LSC-6 board (docs/protocol/lsc-6.md). The board's only
// answers are 55 55 02 <cmd>; none says which request it answers, so callers pair them by
// order and by time. The link sends one request, then reads answers until one is taken or the
// deadline passes; GroupFinished notices that arrive meanwhile are counted, anything else that
// is not an LSC-6 answer is skipped and counted, and a frame of the xArm dialect's battery reply
// is counted as the other dialect answering. The waiting itself (slices on the injected clock,
// the interrupt flag, hang-ups, garbage) is FrameLink's, shared with ControllerLink.
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "base/result.hpp"
#include "protocol/lsc6/lsc6_messages.hpp"
#include "runtime/upload/frame_link.hpp"

namespace seqc::upload {

struct Lsc6Wait {
  WaitStatus status = WaitStatus::Timeout;
  lsc6::Reply reply;
  std::string message;
  bool ok() const { return status == WaitStatus::Matched; }
};

class Lsc6Link : public FrameLink {
 public:
  using FrameLink::FrameLink;

  Status send(const lsc6::Request& request);
  // Reads until `take` accepts an answer or `deadline` passes. Answers not taken are counted in
  // skipped(); GroupFinished notices are also counted in finished_notices().
  Lsc6Wait wait_for(const std::function<bool(const lsc6::Reply&)>& take, io::TimePoint deadline);
  // The answers that have already arrived, without waiting (HangUp/Error in `status`).
  std::vector<lsc6::Reply> drain(WaitStatus& status);

  std::size_t finished_notices() const { return finished_; }
  std::size_t skipped() const { return skipped_; }
  // Replies of the xArm dialect to GetBatteryVoltage (55 55 04 0f lo hi) among the frames read:
  // a board of that dialect is on the line.
  std::size_t other_dialect_replies() const { return other_dialect_; }

 private:
  // The frame as an LSC-6 answer, counting what it is; an error for a frame that is none.
  Result<lsc6::Reply> answer(const lsc::Frame& frame);

  std::size_t finished_ = 0;
  std::size_t skipped_ = 0;
  std::size_t other_dialect_ = 0;
};

}  // namespace seqc::upload
