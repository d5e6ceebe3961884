// Request/response over a byte link to the servo controller.
//
// The controller answers requests in the order it receives them, and also sends frames
// nobody asked for (group started / stopped / finished). ControllerLink sends one request,
// then reads replies until one satisfies the caller's predicate or the deadline passes. Every
// other frame is skipped and reported to the observer; bytes that do not form a frame are
// skipped by the decoder, which resynchronises on the next 55 55.
//
// Waiting happens in slices of at most `slice` (100 ms) on the injected clock, and the
// interrupt flag is polled between slices, so Ctrl-C ends any wait within one slice.
// A device that goes away (HangUp) is reported as such, never as a timeout.
//
// The link never sleeps or reads the wall clock itself: all time comes from the Clock, and
// all waiting happens inside Transport::read with an absolute deadline on that clock.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>

#include "runtime/io/clock.hpp"
#include "runtime/io/transport.hpp"
#include "protocol/lsc_messages.hpp"
#include "protocol/lsc_stream.hpp"
#include "base/result.hpp"

namespace seqc::upload {

// Told about everything the link skips; default implementations ignore it.
class LinkObserver {
 public:
  virtual ~LinkObserver() = default;
  // An unsolicited group notification (GroupStarted, GroupStopped, GroupFinished).
  virtual void on_notification(const lsc::Reply& /*reply*/) {}
  // A well-formed reply the waiting predicate did not take (not a notification).
  virtual void on_unexpected(const lsc::Reply& /*reply*/) {}
  // A whole frame that is not any reply the controller is known to send.
  virtual void on_unparsed(const lsc::Frame& /*frame*/, const std::string& /*why*/) {}
};

enum class WaitStatus {
  Matched,      // the predicate took a reply (in WaitResult::reply)
  Timeout,      // the deadline passed first
  HangUp,       // the device went away
  Interrupted,  // the interrupt flag was set
  Error,        // a read or write failed; see message
};

const char* to_string(WaitStatus status);

struct WaitResult {
  WaitStatus status = WaitStatus::Timeout;
  lsc::Reply reply;
  std::string message;
  bool ok() const { return status == WaitStatus::Matched; }
};

// What a predicate says about one reply: take it (ends the wait), skip it (reported to the
// observer as unexpected), or consume it (the predicate dealt with it; not reported).
enum class Verdict { Take, Skip, Consume };
using ReplyPredicate = std::function<Verdict(const lsc::Reply&)>;

// Whether a wait ends when the interrupt flag is raised. Ignore is for the reply awaited after
// Ctrl-C while the controller is put in a known state, always with a short deadline.
enum class OnInterrupt { Stop, Ignore };

struct LinkStats {
  std::size_t frames_sent = 0;
  std::size_t bytes_sent = 0;
  std::size_t bytes_received = 0;
  std::size_t frames_received = 0;
  std::size_t garbage_bytes = 0;  // skipped while resynchronising
};

class ControllerLink {
 public:
  // `interrupted` may be null. The transport and clock must outlive the link.
  ControllerLink(io::Transport& transport, io::Clock& clock,
                 const std::atomic<bool>* interrupted = nullptr);

  void set_observer(LinkObserver* observer) { observer_ = observer; }
  // Encodes and writes one request. Error if it cannot be encoded or written.
  Status send(const lsc::Request& request);
  // Writes one already-encoded frame (serial form).
  Status send_bytes(ByteView bytes);

  // Reads until `accept` takes a reply or `deadline` passes. Replies already decoded and
  // buffered are looked at first.
  WaitResult wait_for(const ReplyPredicate& accept, io::TimePoint deadline,
                      OnInterrupt on_interrupt = OnInterrupt::Stop);

  // Hands every reply that has already arrived (without waiting) to `seen`, which may not
  // take any: used to clear out stale frames before sending. Returns HangUp/Error if the
  // device went away, Timeout otherwise.
  WaitStatus drain(const std::function<void(const lsc::Reply&)>& seen);

  // Drops everything pending, in the decoder and in the transport.
  void discard_input();
  // After a HangUp: Transport::reopen, then starts afresh (a frame half-read before the
  // hang-up is dropped). True when the link works again.
  bool reopen(io::TimePoint deadline);
  // Drops the start of a frame held in the decoder (after a timeout: a reply whose LEN byte
  // was corrupted upwards would otherwise swallow the replies that follow). Returns the
  // number of bytes dropped.
  std::size_t drop_partial_frame();

  bool interrupted() const { return interrupted_ != nullptr && interrupted_->load(); }
  io::Clock& clock() { return clock_; }
  io::Transport& transport() { return transport_; }
  double seconds_per_byte() const { return transport_.seconds_per_byte(); }
  LinkStats stats() const;

 private:
  // The next decoded reply, skipping and reporting frames that are not replies.
  std::optional<lsc::Reply> next_reply();
  // One read with `deadline`; feeds the decoder. Returns the transport's status.
  io::ReadResult read_some(io::TimePoint deadline);
  void report_skipped(const lsc::Reply& reply);

  io::Transport& transport_;
  io::Clock& clock_;
  const std::atomic<bool>* interrupted_;
  LinkObserver* observer_ = nullptr;
  io::Duration slice_ = std::chrono::milliseconds(100);
  lsc::FrameDecoder decoder_;
  LinkStats stats_;
  std::size_t dropped_partial_ = 0;
};

// True for the frames a controller sends on its own (group started / stopped / finished).
bool is_notification(const lsc::Reply& reply);

}  // namespace seqc::upload
