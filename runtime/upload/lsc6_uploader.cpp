// The LSC-6 download (rules in lsc6_uploader.hpp): one attempt after another from index 0,
// each frame stop-and-wait, with the wait for owed answers after a re-send.
#include "runtime/upload/lsc6_uploader.hpp"

#include <cmath>
#include <optional>
#include <string>
#include <type_traits>
#include <variant>

#include "protocol/dialects.hpp"
#include "protocol/lsc/lsc_messages.hpp"
#include "runtime/io/time_text.hpp"

namespace seqc::upload {
namespace {

constexpr std::size_t kAnswerBytes = 4;

// The DownloadAction a frame carries; nullptr for any other frame.
const lsc6::DownloadAction* action_of(const PlannedFrame& frame) {
  return std::visit(
      [](const auto& request) -> const lsc6::DownloadAction* {
        if constexpr (std::is_same_v<std::decay_t<decltype(request)>, lsc6::Request>) {
          return std::get_if<lsc6::DownloadAction>(&request);
        } else {
          return nullptr;
        }
      },
      frame.request);
}

bool is_stored(const lsc6::Reply& r) { return std::holds_alternative<lsc6::ActionStored>(r); }

class Lsc6Run {
 public:
  Lsc6Run(Lsc6Link& link, const std::vector<PlannedFrame>& plan, const UploadOptions& options,
          UploadObserver* observer)
      : link_(link), plan_(plan), opt_(options), observer_(observer) {}

  UploadResult go();

 private:
  enum class Flow { Ok, Restart, Fatal };

  std::string prepare();
  Flow attempt();
  Flow exchange(std::size_t i);
  Flow fatal(UploadStatus status, std::string message) {
    result_.status = status;
    result_.message = std::move(message);
    return Flow::Fatal;
  }
  Flow wait_failure(const Lsc6Wait& w, const std::string& doing);
  // GetBatteryVoltage (the xArm dialect's), waiting one short deadline; returns that wait, which
  // takes a late ActionStored too.
  Lsc6Wait ask_battery();
  io::Duration timeout(std::size_t i) const;
  void note(const std::string& text) {
    if (observer_ != nullptr) observer_->on_note(text);
  }
  void progress();
  void start_group();
  GroupState state() const;
  const std::string& what(std::size_t i) const { return plan_[i].what; }

  Lsc6Link& link_;
  const std::vector<PlannedFrame>& plan_;  // encoded and labelled by plan_frames()
  UploadOptions opt_;
  UploadObserver* observer_;
  UploadResult result_;
  io::TimePoint start_{0};
  std::size_t done_ = 0;
  bool first_sent_ = false;    // index 0 went out (the group may be erased)
  bool first_stored_ = false;  // index 0 was answered (it is)
  bool last_sent_ = false;     // the last index went out (the count may be written)
  bool completed_ = false;
  std::string restart_reason_;
  UploadStatus restart_status_ = UploadStatus::NoAck;
};

std::string Lsc6Run::prepare() {
  if (plan_.empty()) return "the download plan is empty";
  for (const PlannedFrame& f : plan_) {
    const lsc6::DownloadAction* a = action_of(f);
    if (a == nullptr) return "the download plan holds a frame that is not a DownloadAction";
    if (a->group != opt_.group) {
      return "the download plan is for group " + std::to_string(a->group) + ", not group " +
             std::to_string(opt_.group);
    }
  }
  return "";
}

io::Duration Lsc6Run::timeout(std::size_t i) const {
  const double wire =
      static_cast<double>(plan_[i].bytes.size() + kAnswerBytes) * link_.seconds_per_byte();
  io::Duration d = io::Duration(static_cast<long long>(std::ceil(wire * 1e9))) + opt_.reply_margin;
  if (i == 0) d += kLsc6EraseMargin;
  if (i + 1 == plan_.size()) d += kLsc6CommitMargin;
  return d;
}

Lsc6Run::Flow Lsc6Run::wait_failure(const Lsc6Wait& w, const std::string& doing) {
  switch (w.status) {
    case WaitStatus::HangUp:
      return fatal(UploadStatus::HangUp, "the board went away (" + w.message + ") while " + doing);
    case WaitStatus::Interrupted:
      return fatal(UploadStatus::Interrupted, "interrupted while " + doing);
    default:
      return fatal(UploadStatus::LinkError, "reading from " + link_.transport().describe() +
                                                " failed while " + doing + ": " + w.message);
  }
}

Lsc6Wait Lsc6Run::ask_battery() {
  const Bytes request = lsc::encode_serial(lsc::Request{lsc::GetBatteryVoltage{}}).value();
  if (!link_.send_bytes(request)) return Lsc6Wait{};
  // The request and a voltage reply (55 55 04 0f lo hi) on the wire, plus the margin.
  const double wire = static_cast<double>(request.size() + 6) * link_.seconds_per_byte();
  return link_.wait_for(is_stored, link_.clock().now() +
                                       io::Duration(static_cast<long long>(std::ceil(wire * 1e9))) +
                                       opt_.reply_margin);
}

void Lsc6Run::progress() {
  if (observer_ == nullptr) return;
  UploadProgress p;
  p.actions_done = done_;
  p.actions_total = plan_.size();
  p.frames_done = done_;
  p.frames_total = plan_.size();
  const LinkStats s = link_.stats();
  p.bytes_sent = s.bytes_sent;
  p.bytes_received = s.bytes_received;
  p.elapsed = link_.clock().now() - start_;
  p.attempt = result_.restarts + 1;
  observer_->on_progress(p);
}

// One frame until its answer, then the answers a re-sent frame may still be owed.
Lsc6Run::Flow Lsc6Run::exchange(std::size_t i) {
  WaitStatus st{};
  const std::vector<lsc6::Reply> early = link_.drain(st);
  if (st == WaitStatus::HangUp || st == WaitStatus::Error) {
    return wait_failure(Lsc6Wait{st, {}, "read failed"}, "reading answers");
  }
  for (const lsc6::Reply& r : early) {
    if (!is_stored(r)) continue;
    ++result_.stale_acks;
    restart_reason_ = "an answer arrived that no frame was owed (before " + what(i) + ")";
    restart_status_ = UploadStatus::Inconsistent;
    return Flow::Restart;
  }
  const io::Duration limit = timeout(i);
  int sends = 0;
  for (;;) {
    if (link_.interrupted()) return fatal(UploadStatus::Interrupted, "interrupted");
    const io::TimePoint sent_at = link_.clock().now();
    if (auto ok = link_.send_bytes(plan_[i].bytes); !ok) {
      return fatal(UploadStatus::LinkError, "writing to " + link_.transport().describe() +
                                                " failed while sending " + what(i) + ": " +
                                                ok.error().message);
    }
    ++sends;
    if (i == 0) first_sent_ = true;
    if (i + 1 == plan_.size()) last_sent_ = true;
    Lsc6Wait w = link_.wait_for(is_stored, sent_at + limit);
    if (w.status == WaitStatus::Timeout && i == 0 && sends == 1 && result_.restarts == 0) {
      w = ask_battery();
      if (link_.other_dialect_replies() > 0) {
        // That dialect has no command 25: nothing was stored or erased.
        first_sent_ = false;
        last_sent_ = false;
        return fatal(UploadStatus::OtherDialect,
                     "the board on " + link_.transport().describe() +
                         " does not answer a DownloadAction but answers GetBatteryVoltage with "
                         "its voltage: it speaks the " +
                         std::string(kXarmDialect.name) + " dialect");
      }
    }
    if (w.ok()) break;
    if (w.status != WaitStatus::Timeout) return wait_failure(w, "waiting for " + what(i));
    if (sends > opt_.retries) {
      restart_reason_ = "the board did not answer " + what(i) + " (" + std::to_string(sends) +
                        " attempts, " + io::seconds_text(limit) + " each)";
      restart_status_ = UploadStatus::NoAck;
      return Flow::Restart;
    }
    ++result_.retries;
    if (observer_ != nullptr) {
      observer_->on_retry(RetryEvent{what(i), sends + 1, opt_.retries + 1,
                                     "no answer within " + io::seconds_text(limit)});
    }
  }
  // Each sending earns at most one answer: wait for those still owed before the next frame.
  for (int owed = sends - 1; owed > 0; --owed) {
    const Lsc6Wait w = link_.wait_for(is_stored, link_.clock().now() + limit);
    if (w.status == WaitStatus::Timeout) break;
    if (!w.ok()) return wait_failure(w, "waiting for late answers");
    ++result_.stale_acks;
    note("discarded a late answer to " + what(i));
  }
  if (i == 0) first_stored_ = true;
  return Flow::Ok;
}

Lsc6Run::Flow Lsc6Run::attempt() {
  done_ = 0;
  progress();
  for (std::size_t i = 0; i < plan_.size(); ++i) {
    const Flow f = exchange(i);
    if (f != Flow::Ok) return f;
    ++done_;
    progress();
  }
  return Flow::Ok;
}

void Lsc6Run::start_group() {
  if (!link_.send(lsc6::Run{opt_.group, opt_.run_times})) {
    note("could not send Run");
    return;
  }
  result_.run_sent = true;
  const io::Duration wire = std::chrono::duration_cast<io::Duration>(
      std::chrono::duration<double>(11 * link_.seconds_per_byte()));
  const Lsc6Wait w = link_.wait_for(
      [](const lsc6::Reply& r) { return std::holds_alternative<lsc6::RunAccepted>(r); },
      link_.clock().now() + wire + opt_.reply_margin);
  if (w.ok()) {
    result_.run_reported = true;
  } else if (w.status == WaitStatus::Interrupted) {
    // Ctrl-C while the group was starting: it is stored, but the robot must not move (the
    // Stop follows in go()).
    fatal(UploadStatus::Interrupted,
          "interrupted after starting group " + std::to_string(opt_.group));
  } else {
    note(
        "the board did not answer Run (some copies of its firmware never do): started, "
        "unconfirmed");
  }
}

GroupState Lsc6Run::state() const {
  if (completed_) return GroupState::Stored;
  if (last_sent_) return GroupState::Uncertain;
  if (first_stored_ || first_sent_) return GroupState::OldCount;
  return GroupState::Unchanged;
}

UploadResult Lsc6Run::go() {
  if (auto bad = prepare(); !bad.empty()) {
    result_.status = UploadStatus::BadPlan;
    result_.message = bad;
    return result_;
  }
  result_.actions_total = plan_.size();
  start_ = link_.clock().now();
  link_.discard_input();
  Flow flow = Flow::Fatal;
  if (link_.send(lsc6::Stop{})) {
    for (;;) {
      flow = attempt();
      if (flow != Flow::Restart) break;
      if (result_.restarts >= opt_.restarts) {
        const bool none = restart_status_ == UploadStatus::NoAck && !first_stored_ && done_ == 0;
        flow = fatal(none ? UploadStatus::NoAnswer : restart_status_,
                     none ? "no answer from an LSC-6 board on " + link_.transport().describe() +
                                " (" + restart_reason_ +
                                "); check the port, the cable and that the board is switched on"
                          : restart_reason_ + "; gave up after " +
                                std::to_string(result_.restarts + 1) + " attempts");
        break;
      }
      ++result_.restarts;
      if (observer_ != nullptr) {
        observer_->on_restart(
            RestartEvent{result_.restarts + 1, opt_.restarts + 1, restart_reason_});
      }
    }
  } else {
    flow = fatal(UploadStatus::LinkError, "cannot write to " + link_.transport().describe());
  }
  if (flow == Flow::Ok) {
    completed_ = true;
    result_.status = UploadStatus::Completed;
    if (opt_.run && opt_.may_run && !opt_.may_run(link_.transport(), link_.clock())) {
      result_.run_refused = true;
    } else if (opt_.run) {
      start_group();
    }
  }
  if (result_.status == UploadStatus::Interrupted && result_.run_sent) {
    result_.stop_sent = static_cast<bool>(link_.send(lsc6::Stop{}));
  }
  result_.actions_acknowledged = done_;
  result_.group_state = state();
  result_.elapsed = link_.clock().now() - start_;
  result_.link = link_.stats();
  return result_;
}

}  // namespace

UploadResult upload_lsc6(Lsc6Link& link, const std::vector<PlannedFrame>& plan,
                         const UploadOptions& options, UploadObserver* observer) {
  return Lsc6Run(link, plan, options, observer).go();
}

UploadResult upload_lsc6(Lsc6Link& link, const std::vector<lsc6::DownloadAction>& plan,
                         const UploadOptions& options, UploadObserver* observer) {
  auto frames = plan_frames(plan);
  if (!frames) {
    UploadResult result;
    result.status = UploadStatus::BadPlan;
    result.message = "cannot encode the download plan: " + frames.error().message;
    return result;
  }
  return upload_lsc6(link, *frames, options, observer);
}

}  // namespace seqc::upload
