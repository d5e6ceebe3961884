// Request/response over a byte link to a controller of the xArm / LSC-16 / LSC-32 dialect.
//
// The controller answers requests in the order it receives them, and also sends frames
// nobody asked for (group started / stopped / finished). ControllerLink sends one request,
// then reads replies until one satisfies the caller's predicate or the deadline passes. Every
// other frame is skipped and reported to the observer. What counts as a reply is this dialect's
// (lsc::decode_reply); the waiting itself (slices on the injected clock, the interrupt flag,
// hang-ups, garbage, frames that are no reply) is FrameLink's, shared with the LSC-6's link.
#pragma once

#include <functional>
#include <string>

#include "base/result.hpp"
#include "protocol/lsc/lsc_messages.hpp"
#include "runtime/upload/frame_link.hpp"

namespace seqc::upload {

// Told about everything the link skips; default implementations ignore it.
class LinkObserver : public FrameObserver {
 public:
  // An unsolicited group notification (GroupStarted, GroupStopped, GroupFinished).
  virtual void on_notification(const lsc::Reply& /*reply*/) {}
  // A well-formed reply the waiting predicate did not take (not a notification).
  virtual void on_unexpected(const lsc::Reply& /*reply*/) {}
};

struct WaitResult {
  WaitStatus status = WaitStatus::Timeout;
  lsc::Reply reply;  // Matched: the reply the predicate took
  std::string message;
  bool ok() const { return status == WaitStatus::Matched; }
};

// What a predicate says about one reply: take it (ends the wait), skip it (reported to the
// observer as unexpected), or consume it (the predicate dealt with it; not reported).
enum class Verdict { Take, Skip, Consume };
using ReplyPredicate = std::function<Verdict(const lsc::Reply&)>;

class ControllerLink : public FrameLink {
 public:
  using FrameLink::FrameLink;

  void set_observer(LinkObserver* observer);
  // Encodes and writes one request. Error if it cannot be encoded or written.
  Status send(const lsc::Request& request);

  // Reads until `accept` takes a reply or `deadline` passes. Replies already decoded and
  // buffered are looked at first.
  WaitResult wait_for(const ReplyPredicate& accept, io::TimePoint deadline,
                      OnInterrupt on_interrupt = OnInterrupt::Stop);

  // Hands every reply that has already arrived (without waiting) to `seen`, which may not
  // take any: used to clear out stale frames before sending. Returns HangUp/Error if the
  // device went away, Timeout otherwise.
  WaitStatus drain(const std::function<void(const lsc::Reply&)>& seen);

 private:
  void report_skipped(const lsc::Reply& reply);

  LinkObserver* observer_ = nullptr;
};

// True for the frames a controller sends on its own (group started / stopped / finished).
bool is_notification(const lsc::Reply& reply);

}  // namespace seqc::upload
