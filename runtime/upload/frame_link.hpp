// The byte side of a link to a servo controller, shared by both dialects' links (ControllerLink
// for the xArm / LSC-16 / LSC-32 dialect, Lsc6Link for the LSC-6): `55 55 LEN CMD DATA` frames
// written to and read from a Transport. The dialect's link says what a frame means (OnFrame);
// this class never looks inside one.
//
// Waiting happens in slices of at most 100 ms on the injected clock, and the interrupt flag is
// polled between slices, so Ctrl-C ends any wait within one slice. A device that goes away
// (HangUp) is reported as such, never as a timeout. Bytes that do not form a frame are skipped
// by the decoder, which resynchronises on the next 55 55; whole frames the dialect does not take
// for any of its replies go to the observer.
//
// The link never sleeps or reads the wall clock itself: all time comes from the Clock, and all
// waiting happens inside Transport::read with an absolute deadline on that clock (or in
// Clock::sleep_until, when a transport gives up before its deadline).
#pragma once

#include <atomic>
#include <cstddef>
#include <functional>
#include <string>

#include "base/result.hpp"
#include "protocol/lsc/lsc_frame.hpp"
#include "protocol/lsc/lsc_stream.hpp"
#include "runtime/io/clock.hpp"
#include "runtime/io/transport.hpp"

namespace seqc::upload {

// Told about whole frames the link skips; the default ignores them.
class FrameObserver {
 public:
  virtual ~FrameObserver() = default;
  // A whole frame that is not any reply the board is known to send.
  virtual void on_unparsed(const lsc::Frame& /*frame*/, const std::string& /*why*/) {}
};

enum class WaitStatus {
  Matched,      // the dialect took a reply
  Timeout,      // the deadline passed first
  HangUp,       // the device went away
  Interrupted,  // the interrupt flag was set
  Error,        // a read or write failed; see message
};

const char* to_string(WaitStatus status);

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

// How a wait on frames ended; `message` holds the transport's words for HangUp and Error.
struct FrameWait {
  WaitStatus status = WaitStatus::Timeout;
  std::string message;
};

class FrameLink {
 public:
  // What the dialect makes of one frame: true ends the wait (the reply it waited for), false
  // goes on, an error says the frame is none of the dialect's replies (reported as unparsed).
  using OnFrame = std::function<Result<bool>(const lsc::Frame&)>;

  // `interrupted` may be null. The transport and clock must outlive the link.
  FrameLink(io::Transport& transport, io::Clock& clock,
            const std::atomic<bool>* interrupted = nullptr);

  void set_frame_observer(FrameObserver* observer) { frame_observer_ = observer; }
  // Writes one already-encoded frame (serial form).
  Status send_bytes(ByteView bytes);

  // Hands every frame to `on_frame`, those already buffered first, until it returns true
  // (Matched), `deadline` passes (Timeout), the interrupt flag is raised (Interrupted; not with
  // OnInterrupt::Ignore), the device goes away (HangUp) or a read fails (Error).
  FrameWait wait_frames(const OnFrame& on_frame, io::TimePoint deadline,
                        OnInterrupt on_interrupt = OnInterrupt::Stop);
  // Hands every frame that has already arrived to `on_frame` without waiting (what it returns
  // ends nothing). HangUp/Error if the device went away or failed, Timeout otherwise.
  WaitStatus drain_frames(const OnFrame& on_frame);

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
  // Hands the buffered frames to `on_frame`; true as soon as it takes one.
  bool take_buffered(const OnFrame& on_frame);
  // One read with `deadline`; feeds the decoder. Returns the transport's status.
  io::ReadResult read_some(io::TimePoint deadline);

  io::Transport& transport_;
  io::Clock& clock_;
  const std::atomic<bool>* interrupted_;
  FrameObserver* frame_observer_ = nullptr;
  io::Duration slice_ = std::chrono::milliseconds(100);
  lsc::FrameDecoder decoder_;
  LinkStats stats_;
  std::size_t dropped_partial_ = 0;
};

}  // namespace seqc::upload
