#include "runtime/upload/uploader.hpp"

#include <cmath>
#include <cstdio>
#include <utility>
#include <variant>

#include "runtime/protocol/group_download.hpp"

namespace seqc::upload {
namespace {

// Serial sizes used for deadlines: an ack is 55 55 04 05 step status; GetBatteryVoltage is
// 55 55 02 0f and its reply 55 55 04 0f lo hi.
constexpr std::size_t kAckBytes = 6;
constexpr std::size_t kProbeBytes = 4;
constexpr std::size_t kProbeReplyBytes = 6;

std::string seconds_text(io::Duration d) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f s", std::chrono::duration<double>(d).count());
  return buf;
}

std::string hex2(unsigned v) {
  char buf[8];
  std::snprintf(buf, sizeof buf, "%02x", v & 0xffu);
  return buf;
}

struct PlannedFrame {
  int step = 0;
  Bytes bytes;
  std::string what;
  bool is_action = false;
};

std::uint8_t group_of(const lsc::Request& r) {
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

}  // namespace

const char* to_string(UploadStatus status) {
  switch (status) {
    case UploadStatus::Completed:
      return "completed";
    case UploadStatus::BadPlan:
      return "bad plan";
    case UploadStatus::NoAnswer:
      return "no answer";
    case UploadStatus::NoAck:
      return "no acknowledgement";
    case UploadStatus::Refused:
      return "refused";
    case UploadStatus::Inconsistent:
      return "inconsistent acknowledgements";
    case UploadStatus::HangUp:
      return "hang-up";
    case UploadStatus::Interrupted:
      return "interrupted";
    case UploadStatus::LinkError:
      return "link error";
  }
  return "?";
}

std::string describe_group_state(GroupState state, std::uint8_t group) {
  const std::string g = "group " + std::to_string(group);
  switch (state) {
    case GroupState::Unchanged:
      return g + " is unchanged";
    case GroupState::MaybeErased:
      return g +
             " is unchanged, unless the controller acted on the opening frame it never "
             "acknowledged (then it is empty)";
    case GroupState::Empty:
      return g +
             " is now empty (the controller erased it; it only becomes valid when a "
             "download completes)";
    case GroupState::Uncertain:
      return g +
             " holds what the controller stored last, which may not match the file; "
             "upload again";
    case GroupState::Stored:
      return g + " holds the acknowledged actions";
  }
  return g;
}

Uploader::Uploader(ControllerLink& link, UploadOptions options, UploadObserver* observer)
    : link_(link), options_(options), observer_(observer) {}

io::Duration Uploader::reply_timeout(std::size_t frame_bytes, std::size_t reply_bytes,
                                     bool open) const {
  const double wire = static_cast<double>(frame_bytes + reply_bytes) * link_.seconds_per_byte();
  const auto wire_ns = io::Duration(static_cast<long long>(std::ceil(wire * 1e9)));
  return wire_ns + (open ? options_.open_margin : options_.reply_margin);
}

// One upload: the state of the handshake and the rules from the header, in one place.
class Uploader::Run final : public LinkObserver {
 public:
  Run(Uploader& up, const std::vector<lsc::Request>& plan) : up_(up), plan_(plan) {}

  UploadResult go() {
    result_.actions_total = 0;
    if (auto bad = prepare(); !bad.empty()) {
      result_.status = UploadStatus::BadPlan;
      result_.message = bad;
      return result_;
    }
    link().set_observer(this);
    start_ = clock().now();
    finish(sequence());
    link().set_observer(nullptr);
    result_.elapsed = clock().now() - start_;
    result_.link = link().stats();
    return result_;
  }

  // LinkObserver: everything skipped becomes a note.
  void on_notification(const lsc::Reply& reply) override {
    if (const auto* started = std::get_if<lsc::GroupStarted>(&reply)) {
      if (started->group == opt().group && run_sent_) result_.run_reported = true;
    }
    note("controller says: " + lsc::describe(reply));
  }
  void on_unexpected(const lsc::Reply& reply) override {
    note("skipped an unexpected reply: " + lsc::describe(reply));
  }
  void on_unparsed(const lsc::Frame& frame, const std::string& why) override {
    auto bytes = lsc::encode_serial(frame);
    note("skipped a frame that is no known reply (" + why + ")" +
         (bytes ? ": " + to_hex(*bytes) : std::string()));
  }

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

  void note(const std::string& text) {
    if (up_.observer_ != nullptr) up_.observer_->on_note(text);
  }
  void retry(const std::string& what, int attempt, const std::string& reason) {
    ++result_.retries;
    // Whatever part of a frame is held now will not be completed by the re-send's reply.
    if (const std::size_t n = link().drop_partial_frame(); n > 0) {
      note("dropped " + std::to_string(n) + " bytes of an unfinished reply");
    }
    if (up_.observer_ != nullptr) {
      up_.observer_->on_retry(RetryEvent{what, attempt, max_attempts(), reason});
    }
  }
  void progress() {
    if (up_.observer_ == nullptr) return;
    UploadProgress p;
    p.actions_done = actions_done_;
    p.actions_total = result_.actions_total;
    p.frames_done = frames_done_;
    p.frames_total = frames_.size();
    const LinkStats s = link().stats();
    p.bytes_sent = s.bytes_sent;
    p.bytes_received = s.bytes_received;
    p.elapsed = clock().now() - start_;
    p.attempt = result_.restarts + 1;
    up_.observer_->on_progress(p);
  }

  Flow fatal(UploadStatus status, std::string message) {
    fail_ = Fail{status, std::move(message)};
    return Flow::Fatal;
  }
  Flow wait_failure(const WaitResult& w, const std::string& doing) {
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
  Flow send(ByteView bytes, const std::string& doing) {
    auto st = link().send_bytes(bytes);
    if (st) return Flow::Ok;
    return fatal(UploadStatus::LinkError, "writing to " + link().transport().describe() +
                                              " failed while " + doing + ": " + st.error().message);
  }

  // Checks the plan and encodes every frame; returns an error message or "".
  std::string prepare() {
    if (plan_.empty()) return "the download plan is empty";
    int last_step = 0;
    for (const auto& r : plan_) {
      const int step = lsc::group_download_step(r);
      if (step == 0) return "the download plan holds a request that is not a GroupDownload step";
      if (group_of(r) != opt().group) {
        return "the download plan is for group " + std::to_string(group_of(r)) + ", not group " +
               std::to_string(opt().group);
      }
      if (step < last_step) return "the download plan's steps are out of order";
      last_step = step;
      auto bytes = lsc::encode_serial(r);
      if (!bytes) return "cannot encode the download plan: " + bytes.error().message;
      PlannedFrame f;
      f.step = step;
      f.bytes = std::move(bytes).value();
      f.is_action = step == 4;
      if (f.is_action) ++result_.actions_total;
      frames_.push_back(std::move(f));
    }
    if (frames_.front().step != 1 || frames_.back().step != 5) {
      return "the download plan must start with step 1 and end with step 5";
    }
    std::size_t n = 0;
    for (std::size_t i = 0; i < frames_.size(); ++i) {
      PlannedFrame& f = frames_[i];
      const lsc::Request& r = plan_[i];
      switch (f.step) {
        case 1:
          f.what = "step 1 (open group " + std::to_string(opt().group) + ")";
          break;
        case 2:
          f.what = "step 2 (size of block " +
                   std::to_string(std::get<lsc::GroupDownloadSize>(r).block) + ")";
          break;
        case 3:
          f.what = "step 3 (block list)";
          break;
        case 4: {
          const auto& a = std::get<lsc::GroupDownloadAction>(r);
          ++n;
          f.what = "step 4 (action " + std::to_string(n) + " of " +
                   std::to_string(result_.actions_total) + ": block " + std::to_string(a.block) +
                   ", index " + std::to_string(a.index) + ")";
          break;
        }
        default:
          f.what = "step 5 (close)";
          break;
      }
    }
    return "";
  }

  // Probe, stop, download (with restarts), run. Sets fail_ on failure.
  Flow sequence() {
    link().discard_input();
    if (probe() != Flow::Ok) return Flow::Fatal;

    if (send(lsc::encode_serial(lsc::Request{lsc::GroupStop{}}).value(), "stopping the group") !=
        Flow::Ok) {
      return Flow::Fatal;
    }
    // Boards that answer GroupStop with "group stopped" are busy until then: a barrier sent
    // at once would be dropped. Boards that do not answer cost this short wait once.
    WaitResult stopped = link().wait_for(
        [](const lsc::Reply& r) {
          return std::holds_alternative<lsc::GroupStopped>(r) ? Verdict::Take : Verdict::Skip;
        },
        clock().now() + up_.reply_timeout(kProbeBytes, kProbeBytes, false) / 5);
    if (stopped.status != WaitStatus::Matched && stopped.status != WaitStatus::Timeout) {
      return wait_failure(stopped, "stopping the group");
    }
    if (barrier(Barrier::Sync, 0) == Flow::Fatal) return Flow::Fatal;

    for (;;) {
      const Flow f = download_once();
      if (f == Flow::Ok) break;
      if (f == Flow::Fatal) return f;
      if (result_.restarts >= opt().restarts) {
        return fatal(UploadStatus::Inconsistent,
                     "the controller's acknowledgements did not pair up with the frames sent (" +
                         restart_reason_ + "), after " + std::to_string(result_.restarts + 1) +
                         " attempts");
      }
      ++result_.restarts;
      note("restarting the download from step 1 (attempt " + std::to_string(result_.restarts + 1) +
           "): " + restart_reason_);
      if (barrier(Barrier::Sync, 0) == Flow::Fatal) return Flow::Fatal;
    }
    completed_ = true;

    if (opt().run) start_group();
    return Flow::Ok;
  }

  Flow probe() {
    const Bytes request = lsc::encode_serial(lsc::Request{lsc::GetBatteryVoltage{}}).value();
    const io::Duration timeout = up_.reply_timeout(kProbeBytes, kProbeReplyBytes, false);
    for (int attempt = 1; attempt <= max_attempts(); ++attempt) {
      if (link().interrupted()) return fatal(UploadStatus::Interrupted, "interrupted");
      if (attempt > 1)
        retry("probe (battery voltage)", attempt, "no reply within " + seconds_text(timeout));
      if (send(request, "asking the controller for its battery voltage") != Flow::Ok) {
        return Flow::Fatal;
      }
      WaitResult w = link().wait_for(
          [](const lsc::Reply& r) {
            return std::holds_alternative<lsc::BatteryVoltage>(r) ? Verdict::Take : Verdict::Skip;
          },
          clock().now() + timeout);
      if (w.ok()) {
        result_.battery_mv = std::get<lsc::BatteryVoltage>(w.reply).millivolts;
        return Flow::Ok;
      }
      if (w.status != WaitStatus::Timeout) {
        return wait_failure(w, "asking the controller for its battery voltage");
      }
    }
    return fatal(UploadStatus::NoAnswer,
                 "no reply from a controller on " + link().transport().describe() + " (asked " +
                     std::to_string(max_attempts()) + " times for its battery voltage, waiting " +
                     seconds_text(timeout) +
                     " each time); check the port, the cable and that the controller is "
                     "switched on");
  }

  enum class Barrier {
    Sync,         // acks before the reply are stale; nothing is concluded from them
    AfterResend,  // acks of `step` (the re-sent frame) are expected; any other is mis-pairing
    Final,        // any ack is mis-pairing, except of step 5 when it was re-sent
  };

  // Sends GetBatteryVoltage until it is answered, discarding acks that arrive first.
  // Flow::Restart when the discarded acks show mis-pairing (restart_reason_ says why).
  Flow barrier(Barrier kind, int tolerated_step, int prev_step = 0) {
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
        const bool expected =
            kind == Barrier::Sync || ack->step == tolerated_step || before_barrier;
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
  Flow drain_before(int prev_step, int current_step) {
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
  Flow download_once() {
    actions_done_ = 0;
    frames_done_ = 0;
    suspect_ = false;
    progress();
    bool need_barrier = false;
    int prev_step = 0;
    bool step5_resent = false;
    for (const PlannedFrame& frame : frames_) {
      if (link().interrupted()) return fatal(UploadStatus::Interrupted, "interrupted");
      Flow f = need_barrier ? barrier(Barrier::AfterResend, prev_step, prev_step)
                            : drain_before(prev_step, frame.step);
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
    if (!need_barrier) {
      if (const Flow d = drain_before(5, 5); d != Flow::Ok) return d;
    }
    const Flow f = barrier(Barrier::Final, step5_resent ? 5 : -1, 5);
    if (f == Flow::Restart) restart_reason_ += " (after step 5)";
    return f;
  }

  io::Duration min_wire_time(std::size_t bytes) {
    // 90 %: baud rates are allowed a few per cent of error on either side.
    const double secs = 0.9 * static_cast<double>(bytes) * link().seconds_per_byte();
    return io::Duration(static_cast<long long>(secs * 1e9));
  }

  void discard_early(const lsc::Reply& r) {
    ++result_.stale_acks;
    note(
        "discarded an acknowledgement that came sooner than the wire allows (a duplicate or "
        "late one): " +
        lsc::describe(r));
  }

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
    if (w.status == WaitStatus::Timeout && early) {
      // Nothing followed the early ack: this link answers faster than its baud rate allows
      // (an unpaced pseudo-terminal, a bridge reporting a nominal rate), so the early ack was
      // the real one. Stop holding acks for the rest of the upload.
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
  Flow exchange(const PlannedFrame& frame, bool& resent) {
    const bool open = frame.step == 1;
    const io::Duration timeout = up_.reply_timeout(frame.bytes.size(), kAckBytes, open);
    bool refused_once = false;
    bool suspect_before_refusal = false;
    resent = false;
    int sends = 0;
    int timeouts = 0;
    for (;;) {
      if (link().interrupted()) return fatal(UploadStatus::Interrupted, "interrupted");
      const io::TimePoint sent_at = clock().now();
      if (send(frame.bytes, "sending " + frame.what) != Flow::Ok) return Flow::Fatal;
      ++sends;
      if (open) step1_unanswered_ = true;
      std::string mispaired;
      WaitResult w = await_ack(frame, sent_at, timeout, mispaired);
      if (w.ok()) {
        if (!mispaired.empty()) {
          ++result_.stale_acks;
          restart_reason_ = mispaired;
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
          if (suspect_before_refusal) {
            // Earlier in this attempt an acknowledgement may have been taken for the wrong
            // frame; a frame sent too early is dropped by the busy controller and the next
            // one is then refused for the gap. That refusal is ours, not the controller's
            // verdict: start again from step 1.
            restart_reason_ = "the controller refused " + frame.what + " (status " +
                              hex2(ack.status) +
                              ") twice, after a re-send or an extra acknowledgement";
            return Flow::Restart;
          }
          return fatal(UploadStatus::Refused, "the controller refused " + frame.what + " (status " +
                                                  hex2(ack.status) + ", twice in a row)");
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
        return fatal(UploadStatus::NoAck, "the controller did not acknowledge " + frame.what +
                                              " (" + std::to_string(sends) + " attempts, " +
                                              seconds_text(timeout) + " each)");
      }
      retry(frame.what, sends + 1, "no acknowledgement within " + seconds_text(timeout));
      resent = true;
      suspect_ = true;
    }
  }

  // GroupRun, then a barrier so a refusal to start or a notification can be seen.
  void start_group() {
    auto bytes = lsc::encode_serial(lsc::Request{lsc::GroupRun{opt().group, opt().run_times}});
    if (!bytes || !link().send_bytes(*bytes)) {
      note("could not send GroupRun");
      return;
    }
    run_sent_ = true;
    result_.run_sent = true;
    // As after GroupStop: a board that announces the start is busy until it does.
    WaitResult started = link().wait_for(
        [this](const lsc::Reply& r) {
          const auto* s = std::get_if<lsc::GroupStarted>(&r);
          return s != nullptr && s->group == opt().group ? Verdict::Take : Verdict::Skip;
        },
        clock().now() + up_.reply_timeout(kProbeBytes, kProbeBytes, false) / 5);
    if (started.ok()) result_.run_reported = true;
    const Flow f = barrier(Barrier::Sync, 0);
    if (f != Flow::Ok) {
      note("the controller did not answer after GroupRun: " + (fail_ ? fail_->message : ""));
      fail_.reset();
    }
  }

  void finish(Flow flow) {
    if (flow == Flow::Ok && completed_) {
      result_.status = UploadStatus::Completed;
      result_.group_state = GroupState::Stored;
      result_.actions_acknowledged = actions_done_;
      return;
    }
    result_.status = fail_ ? fail_->status : UploadStatus::LinkError;
    result_.message = fail_ ? fail_->message : "the upload ended unexpectedly";
    result_.actions_acknowledged = actions_done_;
    if (committed_unconfirmed_) {
      result_.group_state = GroupState::Uncertain;
    } else if (erased_) {
      result_.group_state = GroupState::Empty;
    } else if (step1_unanswered_) {
      result_.group_state = GroupState::MaybeErased;
    } else {
      result_.group_state = GroupState::Unchanged;
    }
  }

  Uploader& up_;
  const std::vector<lsc::Request>& plan_;
  std::vector<PlannedFrame> frames_;
  UploadResult result_;
  io::TimePoint start_{0};
  std::optional<Fail> fail_;
  std::string restart_reason_;
  std::size_t actions_done_ = 0;
  std::size_t frames_done_ = 0;
  bool completed_ = false;
  bool run_sent_ = false;
  bool erased_ = false;                 // step 1 acknowledged since the last step 5
  bool committed_unconfirmed_ = false;  // step 5 acknowledged, final barrier not passed
  bool step1_unanswered_ = false;       // step 1 sent and not (yet) answered
  // This attempt re-sent a frame or saw an extra acknowledgement, so a refusal may be the
  // consequence of a mis-paired acknowledgement rather than the controller's verdict.
  bool suspect_ = false;
  // Whether acks are checked against the time the wire needs (see await_ack).
  bool wire_check_ = true;
};

UploadResult Uploader::upload(const std::vector<lsc::Request>& plan) {
  Run run(*this, plan);
  return run.go();
}

}  // namespace seqc::upload
