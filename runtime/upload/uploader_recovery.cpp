// What the uploader does when an attempt fails (the rules in uploader.hpp): restarting the
// download from step 1 within one budget, reconnecting a port that hung up, and the known
// state an interrupted upload leaves the controller in.
#include "runtime/upload/uploader_run.hpp"

namespace seqc::upload {

void Uploader::Run::announce_restart(const std::string& reason) {
  const int attempt = result_.restarts + 1;
  if (up_.observer_ != nullptr) {
    up_.observer_->on_restart(RestartEvent{attempt, 1 + opt().restarts, reason});
  }
}

auto Uploader::Run::restart() -> Flow {
  if (result_.restarts >= opt().restarts) {
    const int n = result_.restarts + 1;
    const std::string attempts = std::to_string(n) + (n == 1 ? " attempt" : " attempts");
    if (restart_status_ == UploadStatus::Inconsistent) {
      return fatal(UploadStatus::Inconsistent,
                   "the controller's acknowledgements did not pair up with the frames sent (" +
                       restart_reason_ + "), after " + attempts);
    }
    return fatal(restart_status_, restart_reason_ + "; gave up after " + attempts);
  }
  ++result_.restarts;
  announce_restart(restart_reason_);
  return barrier(Barrier::Sync, 0) == Flow::Fatal ? Flow::Fatal : Flow::Ok;
}

auto Uploader::Run::reconnect() -> Flow {
  if (result_.restarts >= opt().restarts) {
    fail_->message += " (no restarts left)";
    return Flow::Fatal;
  }
  note("the port hung up; waiting up to " + seconds_text(opt().reopen_wait) +
       " for the same device to come back");
  if (!link().reopen(clock().now() + opt().reopen_wait)) {
    if (link().interrupted()) return fatal(UploadStatus::Interrupted, "interrupted");
    fail_->message += "; it did not come back within " + seconds_text(opt().reopen_wait);
    return Flow::Fatal;
  }
  const std::string why = fail_->message;
  fail_.reset();
  ++result_.reopens;
  ++result_.restarts;
  // Whatever the controller was doing, the download starts over: probe, stop, step 1.
  stop_sent_ = false;
  announce_restart(why + "; the device came back on " + link().transport().describe());
  return Flow::Ok;
}

void Uploader::Run::secure_after_interrupt() {
  const std::uint8_t group = opt().group;
  // A group may be playing: the one this upload started, or the one that was playing when
  // the upload began, if it was interrupted before stopping it.
  if (run_sent_ || !stop_sent_) {
    auto stop = lsc::encode_serial(lsc::Request{lsc::GroupStop{}});
    result_.stop_sent = stop && static_cast<bool>(link().send_bytes(*stop));
  }
  // Step 5 went out but the group was never confirmed: whatever the controller stored may be
  // incomplete and would look valid. Erasing it leaves a known state: empty.
  if (step5_sent_ && !completed_) {
    auto erase = lsc::encode_serial(lsc::Request{lsc::GroupErase{group}});
    result_.erase_sent = erase && static_cast<bool>(link().send_bytes(*erase));
    if (!result_.erase_sent) return;
    // Only the reply says the erase was done: a controller still busy storing step 5 drops it.
    const io::Duration wait = up_.reply_timeout(erase->size(), kEraseReplyBytes, true);
    const WaitResult w = link().wait_for(
        [](const lsc::Reply& r) {
          return std::holds_alternative<lsc::GroupErased>(r) ? Verdict::Take : Verdict::Skip;
        },
        clock().now() + wait, OnInterrupt::Ignore);
    result_.erase_confirmed = w.ok();
    if (result_.erase_confirmed) {
      committed_unconfirmed_ = false;
      erased_ = true;
    } else {
      // Step 5 may have been stored and the erase lost: nothing is known about the group.
      committed_unconfirmed_ = true;
      note("the controller did not confirm GroupErase of group " + std::to_string(group) +
           " within " + seconds_text(wait));
    }
  }
}

}  // namespace seqc::upload
