// One upload in progress (private to the uploader): the state of the handshake and the rules
// from uploader.hpp. uploader.cpp holds the run's sequence (probe, steps, GroupRun, the final
// verdict); uploader_exchange.cpp holds the exchange of one frame with its acknowledgement and
// the barriers that re-pair requests and replies; uploader_recovery.cpp holds what happens
// when an attempt fails: restarts, reconnecting a port that hung up, and the known state an
// interrupted upload leaves behind.
#pragma once

#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "runtime/io/time_text.hpp"
#include "protocol/lsc/group_download.hpp"
#include "protocol/planned_frame.hpp"
#include "runtime/upload/uploader.hpp"

namespace seqc::upload {

// Serial sizes used for deadlines: an ack is 55 55 04 05 step status; GetBatteryVoltage is
// 55 55 02 0f and its reply 55 55 04 0f lo hi.
inline constexpr std::size_t kAckBytes = 6;
inline constexpr std::size_t kProbeBytes = 4;
inline constexpr std::size_t kProbeReplyBytes = 6;
// GroupErase's reply: 55 55 02 08.
inline constexpr std::size_t kEraseReplyBytes = 4;

using io::seconds_text;

inline std::string hex2(unsigned v) {
  char buf[8];
  std::snprintf(buf, sizeof buf, "%02x", v & 0xffu);
  return buf;
}

inline std::uint8_t group_of(const lsc::Request& r) {
  return std::visit(
      [](const auto& m) -> std::uint8_t {
        if constexpr (requires { m.group; }) {
          return m.group;
        } else {
          return 0;
        }
      },
      r);
}

class Uploader::Run final : public LinkObserver {
 public:
  Run(Uploader& up, const std::vector<PlannedFrame>& plan) : up_(up), frames_(plan) {}

  UploadResult go();

  // LinkObserver: everything skipped becomes a note.
  void on_notification(const lsc::Reply& reply) override;
  void on_unexpected(const lsc::Reply& reply) override;
  void on_unparsed(const lsc::Frame& frame, const std::string& why) override;

 private:
  // How a piece of the sequence ended.
  enum class Flow { Ok, Restart, Fatal };
  struct Fail {
    UploadStatus status;
    std::string message;
  };

  ControllerLink& link() { return up_.link_; }
  io::Clock& clock() { return up_.link_.clock(); }
  const UploadOptions& opt() const { return up_.options_; }
  int max_attempts() const { return 1 + (opt().retries < 0 ? 0 : opt().retries); }

  void note(const std::string& text);
  void retry(const std::string& what, int attempt, const std::string& reason);
  void progress();

  Flow fatal(UploadStatus status, std::string message);
  Flow wait_failure(const WaitResult& w, const std::string& doing);
  Flow send(ByteView bytes, const std::string& doing);

  // Checks the plan (steps in order, one group); returns an error message or "".
  std::string prepare();

  // Probe, stop, download (with restarts and reconnects), run. Sets fail_ on failure.
  Flow sequence();
  // Probe, GroupStop, then the download with its restarts.
  Flow connect_and_download();

  // uploader_recovery.cpp. After download_once returned Restart (restart_reason_ and
  // restart_status_ say why): within the budget, tells the observer and re-synchronises;
  // else fails with the last cause.
  Flow restart();
  // After a HangUp (fail_): within the budget, waits for the port to come back.
  Flow reconnect();
  // Interrupted: GroupStop / GroupErase as uploader.hpp describes.
  void secure_after_interrupt();
  void announce_restart(const std::string& reason);

  Flow probe();
  // After the probe went unanswered: does an LSC-6 answer the LSC-6 question (uploader.hpp)?
  bool answers_as_lsc6();

  enum class Barrier {
    Sync,         // acks before the reply are stale; nothing is concluded from them
    AfterResend,  // acks of `step` (the re-sent frame) are expected; any other is mis-pairing
    Final,        // any ack is mis-pairing, except of step 5 when it was re-sent
  };

  // Sends GetBatteryVoltage until it is answered, discarding acks that arrive first.
  // Flow::Restart when the discarded acks show mis-pairing (restart_reason_ says why).
  Flow barrier(Barrier kind, int tolerated_step, int prev_step = 0);

  // Before a frame is sent: acks that already arrived. A duplicate of the previous frame's
  // ack is harmless here; an ack of an earlier step means an earlier pairing was wrong.
  Flow drain_before(int prev_step, int current_step);

  // Steps 1..5 once.
  Flow download_once();

  // The late-ack guard (UploadOptions::late_guard): until guard_until_, acks of `step` are
  // discarded; an ack of another step is evidence of mis-pairing (Restart).
  Flow late_ack_guard(int step);

  io::Duration min_wire_time(std::size_t bytes);

  void discard_early(const lsc::Reply& r);

  // Waits for `frame`'s ack after it was sent at `sent_at`. `mispaired` is set when an ack
  // of an earlier step was taken instead (then the wait result is Matched).
  WaitResult await_ack(const PlannedFrame& frame, io::TimePoint sent_at, io::Duration timeout,
                       std::string& mispaired) {
    // The frame and its ack need (frame + ack) bytes on the wire: an ack read sooner was sent
    // before this frame arrived (a duplicate or late ack of the previous frame). It is held,
    // not taken; if a proper ack follows, the early one is discarded (rule b).
    const io::TimePoint earliest =
        sent_at + (wire_check_ ? min_wire_time(frame.bytes.size() + kAckBytes) : io::Duration{0});
    std::optional<lsc::Reply> early;
    WaitResult w = link().wait_for(
        [&](const lsc::Reply& r) {
          const auto* ack = std::get_if<lsc::GroupDownloadAck>(&r);
          if (ack == nullptr) return Verdict::Skip;
          if (ack->step == frame.step) {
            if (clock().now() < earliest) {
              if (early) discard_early(*early);
              early = r;
              return Verdict::Consume;
            }
            if (early) discard_early(*early);
            early.reset();
            return Verdict::Take;
          }
          if (ack->step >= 1 && ack->step < frame.step) {
            mispaired = "an " + lsc::describe(r) + " while waiting for " + frame.what;
            return Verdict::Take;
          }
          note("ignored an acknowledgement of a step not sent (corrupted?): " + lsc::describe(r));
          suspect_ = true;
          return Verdict::Consume;
        },
        sent_at + timeout);
    if (w.status == WaitStatus::Timeout && early && ++early_only_ < 2) {
      // Nothing followed the early ack. Either this frame was lost and the early ack was a
      // duplicate of the previous one, or the link is faster than its baud rate. Re-sending
      // is safe in both cases (the controller acknowledges a repeat again), so the first time
      // it counts as no acknowledgement.
      discard_early(*early);
      return w;
    }
    if (w.status == WaitStatus::Timeout && early) {
      // Again: this link answers faster than its baud rate allows (an unpaced pseudo-terminal,
      // a bridge reporting a nominal rate), so the early ack was the real one. Stop holding
      // acks for the rest of the upload.
      wire_check_ = false;
      suspect_ = true;
      note("acknowledgements arrive sooner than " + link().transport().describe() +
           " could carry them; no longer checking their timing against the wire");
      w.status = WaitStatus::Matched;
      w.reply = std::move(*early);
    }
    return w;
  }

  // Sends one frame until its own step's acceptance arrives. `resent` tells whether the
  // frame went out more than once (then a barrier must precede the next frame).
  Flow exchange(const PlannedFrame& frame, bool& resent);

  // GroupRun, then a barrier so a refusal to start or a notification can be seen.
  void start_group();

  void finish(Flow flow);

  Uploader& up_;
  const std::vector<PlannedFrame>& frames_;  // encoded and labelled by plan_frames()
  UploadResult result_;
  io::TimePoint start_{0};
  std::optional<Fail> fail_;
  std::string restart_reason_;
  UploadStatus restart_status_ = UploadStatus::Inconsistent;  // if the budget runs out
  std::vector<int> double_refusals_;  // per frame: attempts in which it was refused twice
  std::size_t actions_done_ = 0;
  std::size_t frames_done_ = 0;
  bool completed_ = false;
  bool run_sent_ = false;
  bool erased_ = false;                 // step 1 acknowledged since the last step 5
  bool committed_unconfirmed_ = false;  // step 5 acknowledged, final barrier not passed
  bool step1_unanswered_ = false;       // step 1 sent and not (yet) answered
  bool stop_sent_ = false;              // this upload's GroupStop went out
  bool step5_sent_ = false;             // step 5 went out in the current attempt
  io::TimePoint guard_until_{0};        // see late_ack_guard
  // This attempt re-sent a frame or saw an extra acknowledgement, so a refusal may be the
  // consequence of a mis-paired acknowledgement rather than the controller's verdict.
  bool suspect_ = false;
  // Whether acks are checked against the time the wire needs (see await_ack).
  bool wire_check_ = true;
  int early_only_ = 0;  // waits in which only an early ack came
};

}  // namespace seqc::upload
