// The exchange of one frame with its acknowledgement, and the barriers that re-pair requests
// and replies after a retry (the rules in uploader.hpp).
#include "runtime/upload/uploader_run.hpp"

namespace seqc::upload {

auto Uploader::Run::wait_failure(const WaitResult& w, const std::string& doing) -> Flow {
  switch (w.status) {
    case WaitStatus::HangUp:
      return fatal(UploadStatus::HangUp,
                   "the controller went away (" + w.message + ") while " + doing);
    case WaitStatus::Interrupted:
      return fatal(UploadStatus::Interrupted, "interrupted while " + doing);
    case WaitStatus::Error:
      return fatal(UploadStatus::LinkError, "reading from " + link().transport().describe() +
                                                " failed while " + doing + ": " + w.message);
    default:
      return fatal(UploadStatus::LinkError, "unexpected wait result while " + doing);
  }
}

auto Uploader::Run::send(ByteView bytes, const std::string& doing) -> Flow {
  auto st = link().send_bytes(bytes);
  if (st) return Flow::Ok;
  return fatal(UploadStatus::LinkError, "writing to " + link().transport().describe() +
                                            " failed while " + doing + ": " + st.error().message);
}

// Sends GetBatteryVoltage until it is answered, discarding acks that arrive first.
// Flow::Restart when the discarded acks show mis-pairing (restart_reason_ says why).
auto Uploader::Run::barrier(Barrier kind, int tolerated_step, int prev_step) -> Flow {
  const Bytes request = lsc::encode_serial(lsc::Request{lsc::GetBatteryVoltage{}}).value();
  const io::Duration timeout = up_.reply_timeout(kProbeBytes, kProbeReplyBytes, false);
  std::string mispaired;
  io::TimePoint earliest{0};
  bool early = false;
  auto classify = [&](const lsc::Reply& r) {
    if (std::holds_alternative<lsc::BatteryVoltage>(r)) {
      // A reply sooner than the wire allows answers an earlier, re-sent barrier.
      if (clock().now() < earliest) {
        early = true;
        return Verdict::Consume;
      }
      return Verdict::Take;
    }
    if (const auto* ack = std::get_if<lsc::GroupDownloadAck>(&r)) {
      ++result_.stale_acks;
      // An ack of the previous frame read sooner than the barrier could have been answered
      // was on its way before the barrier was sent: the same as one drained before it.
      const bool before_barrier = ack->step == prev_step && clock().now() < earliest;
      const bool expected = kind == Barrier::Sync || ack->step == tolerated_step || before_barrier;
      note(std::string(expected ? "discarded a stale acknowledgement: "
                                : "an acknowledgement nothing was waiting for: ") +
           lsc::describe(r));
      if (kind != Barrier::Sync) suspect_ = true;
      if (!expected && mispaired.empty()) mispaired = "an extra " + lsc::describe(r);
      return Verdict::Consume;
    }
    return Verdict::Skip;  // the link reports it
  };
  for (int attempt = 1; attempt <= max_attempts(); ++attempt) {
    if (link().interrupted()) return fatal(UploadStatus::Interrupted, "interrupted");
    if (attempt > 1)
      retry("barrier (battery voltage)", attempt, "no reply within " + seconds_text(timeout));
    const io::TimePoint sent_at = clock().now();
    earliest =
        sent_at + (wire_check_ ? min_wire_time(kProbeBytes + kProbeReplyBytes) : io::Duration{0});
    early = false;
    if (send(request, "checking that the controller has answered everything") != Flow::Ok) {
      return Flow::Fatal;
    }
    WaitResult w = link().wait_for(classify, sent_at + timeout);
    if (w.status == WaitStatus::Timeout && early) {
      wire_check_ = false;  // as in await_ack: the link is faster than its baud rate
      note("replies arrive sooner than " + link().transport().describe() +
           " could carry them; no longer checking their timing against the wire");
      w.status = WaitStatus::Matched;
    }
    if (w.ok()) {
      if (!mispaired.empty()) {
        restart_reason_ = mispaired + " arrived before the barrier's reply";
        return Flow::Restart;
      }
      return Flow::Ok;
    }
    if (w.status != WaitStatus::Timeout) {
      return wait_failure(w, "waiting for the controller to answer a barrier");
    }
  }
  return fatal(UploadStatus::NoAck, "the controller stopped answering (no reply to " +
                                        std::to_string(max_attempts()) +
                                        " battery-voltage requests)");
}

// Before a frame is sent: acks that already arrived. A duplicate of the previous frame's
// ack is harmless here; an ack of an earlier step means an earlier pairing was wrong.
auto Uploader::Run::drain_before(int prev_step, int current_step) -> Flow {
  std::string mispaired;
  const WaitStatus st = link().drain([&](const lsc::Reply& r) {
    if (const auto* ack = std::get_if<lsc::GroupDownloadAck>(&r)) {
      ++result_.stale_acks;
      suspect_ = true;
      if (ack->step == prev_step && ack->accepted()) {
        note("discarded an extra acknowledgement: " + lsc::describe(r));
      } else if (ack->step >= 1 && ack->step <= current_step) {
        if (mispaired.empty()) mispaired = "an unexpected " + lsc::describe(r);
      } else {
        note("ignored an acknowledgement of a step not sent (corrupted?): " + lsc::describe(r));
      }
      return;
    }
    on_unexpected(r);
  });
  if (st == WaitStatus::HangUp) {
    return wait_failure(WaitResult{st, {}, "the device went away"}, "reading replies");
  }
  if (st == WaitStatus::Error) {
    return wait_failure(WaitResult{st, {}, "read failed"}, "reading replies");
  }
  if (!mispaired.empty()) {
    restart_reason_ = mispaired + " arrived between frames";
    return Flow::Restart;
  }
  return Flow::Ok;
}

// Steps 1..5 once.
auto Uploader::Run::download_once() -> Flow {
  actions_done_ = 0;
  frames_done_ = 0;
  suspect_ = false;
  step5_sent_ = false;
  restart_status_ = UploadStatus::Inconsistent;
  progress();
  bool need_barrier = false;
  int prev_step = 0;
  bool step5_resent = false;
  for (const PlannedFrame& frame : frames_) {
    if (link().interrupted()) return fatal(UploadStatus::Interrupted, "interrupted");
    Flow f = need_barrier ? late_ack_guard(prev_step) : drain_before(prev_step, frame.step);
    if (f == Flow::Ok && need_barrier) f = barrier(Barrier::AfterResend, prev_step, prev_step);
    if (f != Flow::Ok) return f;
    bool resent = false;
    f = exchange(frame, resent);
    if (f != Flow::Ok) return f;
    need_barrier = resent;
    if (frame.step == 5) step5_resent = resent;
    prev_step = frame.step;
    ++frames_done_;
    if (frame.is_action) ++actions_done_;
    progress();
  }
  committed_unconfirmed_ = true;
  erased_ = false;
  if (const Flow d = need_barrier ? late_ack_guard(5) : drain_before(5, 5); d != Flow::Ok) {
    return d;
  }
  const Flow f = barrier(Barrier::Final, step5_resent ? 5 : -1, 5);
  if (f == Flow::Restart) restart_reason_ += " (after step 5)";
  return f;
}

auto Uploader::Run::late_ack_guard(int step) -> Flow {
  if (clock().now() >= guard_until_) return Flow::Ok;
  std::string mispaired;
  WaitResult w = link().wait_for(
      [&](const lsc::Reply& r) {
        const auto* ack = std::get_if<lsc::GroupDownloadAck>(&r);
        if (ack == nullptr) return Verdict::Skip;
        ++result_.stale_acks;
        if (ack->step == step) {
          note("discarded a late acknowledgement: " + lsc::describe(r));
        } else if (mispaired.empty()) {
          mispaired = "an extra " + lsc::describe(r);
        }
        return Verdict::Consume;
      },
      guard_until_);
  if (w.status != WaitStatus::Timeout) return wait_failure(w, "waiting for late acknowledgements");
  if (!mispaired.empty()) {
    restart_reason_ = mispaired + " arrived while waiting for late acknowledgements";
    return Flow::Restart;
  }
  return Flow::Ok;
}

io::Duration Uploader::Run::min_wire_time(std::size_t bytes) {
  // 90 %: baud rates are allowed a few per cent of error on either side.
  const double secs = 0.9 * static_cast<double>(bytes) * link().seconds_per_byte();
  return io::Duration(static_cast<long long>(secs * 1e9));
}

void Uploader::Run::discard_early(const lsc::Reply& r) {
  ++result_.stale_acks;
  note(
      "discarded an acknowledgement that came sooner than the wire allows (a duplicate or "
      "late one): " +
      lsc::describe(r));
}

// Sends one frame until its own step's acceptance arrives. `resent` tells whether the
// frame went out more than once (then a barrier must precede the next frame).
auto Uploader::Run::exchange(const PlannedFrame& frame, bool& resent) -> Flow {
  const bool open = frame.step == 1;
  const io::Duration timeout = up_.reply_timeout(frame.bytes.size(), kAckBytes, open);
  bool refused_once = false;
  bool suspect_before_refusal = false;
  resent = false;
  int sends = 0;
  int timeouts = 0;
  io::TimePoint first_sent{0};
  for (;;) {
    if (link().interrupted()) return fatal(UploadStatus::Interrupted, "interrupted");
    const io::TimePoint sent_at = clock().now();
    if (send(frame.bytes, "sending " + frame.what) != Flow::Ok) return Flow::Fatal;
    if (sends++ == 0) first_sent = sent_at;
    if (open) step1_unanswered_ = true;
    if (frame.step == 5) step5_sent_ = true;
    std::string mispaired;
    WaitResult w = await_ack(frame, sent_at, timeout, mispaired);
    if (w.ok()) {
      if (!mispaired.empty()) {
        ++result_.stale_acks;
        restart_reason_ = mispaired;
        restart_status_ = UploadStatus::Inconsistent;
        return Flow::Restart;
      }
      const auto& ack = std::get<lsc::GroupDownloadAck>(w.reply);
      if (open) step1_unanswered_ = false;
      if (ack.accepted()) {
        if (open) {
          erased_ = true;
          committed_unconfirmed_ = false;
        }
        return Flow::Ok;
      }
      if (refused_once) {
        const std::string refused = "the controller refused " + frame.what + " (status " +
                                    hex2(ack.status) + ", twice in a row)";
        // Step 1 refused, or this frame refused the same way in an earlier attempt too: the
        // controller means it.
        if (frame.step == 1 || double_refusals_[frame.index]++ > 0) {
          return fatal(UploadStatus::Refused, refused);
        }
        // Otherwise the refusal may be ours -- earlier in this attempt an acknowledgement
        // was taken for the wrong frame, one sent too early was dropped by the busy
        // controller and this one is refused for the gap -- or the controller reset and
        // forgot the download: either way, start again from step 1.
        restart_reason_ = refused + "; it may have restarted (a power dip forgets a download)" +
                          (suspect_before_refusal
                               ? ", or an earlier acknowledgement was taken for the wrong frame"
                               : "");
        restart_status_ = UploadStatus::Refused;
        return Flow::Restart;
      }
      suspect_before_refusal = suspect_;
      refused_once = true;
      suspect_ = true;
      note("the controller refused " + frame.what + " (status " + hex2(ack.status) +
           "); sending it once more to tell a refusal from a corrupted acknowledgement");
      // Everything the controller still owes must arrive before the confirming attempt.
      if (const Flow b = barrier(Barrier::AfterResend, frame.step); b != Flow::Ok) return b;
      retry(frame.what, sends + 1, "refused once (status " + hex2(ack.status) + ")");
      resent = true;
      continue;
    }
    if (w.status != WaitStatus::Timeout) return wait_failure(w, "waiting for " + frame.what);
    if (++timeouts >= max_attempts()) {
      // A controller that is busy or briefly deaf may take a fresh start; one that is gone
      // fails the restart's first barrier.
      restart_reason_ = "the controller did not acknowledge " + frame.what + " (" +
                        std::to_string(sends) + " attempts, " + seconds_text(timeout) + " each)";
      restart_status_ = UploadStatus::NoAck;
      return Flow::Restart;
    }
    retry(frame.what, sends + 1, "no acknowledgement within " + seconds_text(timeout));
    resent = true;
    suspect_ = true;
    guard_until_ = std::max(guard_until_, first_sent + opt().late_guard);
  }
}

}  // namespace seqc::upload
