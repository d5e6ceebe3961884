#include "runtime/upload/uploader.hpp"

#include "protocol/dialects.hpp"
#include "runtime/upload/dialect_questions.hpp"
#include "runtime/upload/uploader_run.hpp"

namespace seqc::upload {

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
    case UploadStatus::OtherDialect:
      return "another dialect";
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
    case GroupState::OldCount:
      return g +
             " keeps its old action count over actions that were erased or only partly "
             "rewritten (running it stops at the first erased action); upload again";
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
UploadResult Uploader::Run::go() {
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
void Uploader::Run::on_notification(const lsc::Reply& reply) {
  if (const auto* started = std::get_if<lsc::GroupStarted>(&reply)) {
    if (started->group == opt().group && run_sent_) result_.run_reported = true;
  }
  note("controller says: " + lsc::describe(reply));
}

void Uploader::Run::on_unexpected(const lsc::Reply& reply) {
  note("skipped an unexpected reply: " + lsc::describe(reply));
}

void Uploader::Run::on_unparsed(const lsc::Frame& frame, const std::string& why) {
  auto bytes = lsc::encode_serial(frame);
  note("skipped a frame that is no known reply (" + why + ")" +
       (bytes ? ": " + to_hex(*bytes) : std::string()));
}

void Uploader::Run::note(const std::string& text) {
  if (up_.observer_ != nullptr) up_.observer_->on_note(text);
}

void Uploader::Run::retry(const std::string& what, int attempt, const std::string& reason) {
  ++result_.retries;
  // Whatever part of a frame is held now will not be completed by the re-send's reply.
  if (const std::size_t n = link().drop_partial_frame(); n > 0) {
    note("dropped " + std::to_string(n) + " bytes of an unfinished reply");
  }
  if (up_.observer_ != nullptr) {
    up_.observer_->on_retry(RetryEvent{what, attempt, max_attempts(), reason});
  }
}

void Uploader::Run::progress() {
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

auto Uploader::Run::fatal(UploadStatus status, std::string message) -> Flow {
  fail_ = Fail{status, std::move(message)};
  return Flow::Fatal;
}

// Checks the plan (plan_frames() encoded and labelled it); returns an error message or "".
std::string Uploader::Run::prepare() {
  if (frames_.empty()) return "the download plan is empty";
  int last_step = 0;
  for (const PlannedFrame& f : frames_) {
    const auto* r = std::get_if<lsc::Request>(&f.request);
    const int step = r != nullptr ? lsc::group_download_step(*r) : 0;
    if (step == 0) return "the download plan holds a request that is not a GroupDownload step";
    if (group_of(*r) != opt().group) {
      return "the download plan is for group " + std::to_string(group_of(*r)) + ", not group " +
             std::to_string(opt().group);
    }
    if (step < last_step) return "the download plan's steps are out of order";
    last_step = step;
    if (f.is_action) ++result_.actions_total;
  }
  double_refusals_.assign(frames_.size(), 0);
  if (frames_.front().step != 1 || frames_.back().step != 5) {
    return "the download plan must start with step 1 and end with step 5";
  }
  return "";
}

// Probe, stop, download (with restarts and reconnects), run. Sets fail_ on failure.
auto Uploader::Run::sequence() -> Flow {
  link().discard_input();
  for (;;) {
    const Flow f = connect_and_download();
    if (f == Flow::Ok) break;
    if (!fail_ || fail_->status != UploadStatus::HangUp) return Flow::Fatal;
    if (reconnect() != Flow::Ok) return Flow::Fatal;
  }
  completed_ = true;

  if (opt().run && opt().may_run && !opt().may_run(link().transport(), link().clock())) {
    result_.run_refused = true;
  } else if (opt().run) {
    start_group();
  }
  return Flow::Ok;
}

auto Uploader::Run::connect_and_download() -> Flow {
  if (probe() != Flow::Ok) return Flow::Fatal;

  if (send(lsc::encode_serial(lsc::Request{lsc::GroupStop{}}).value(), "stopping the group") !=
      Flow::Ok) {
    return Flow::Fatal;
  }
  stop_sent_ = true;
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
    if (f != Flow::Restart) return f;
    if (restart() != Flow::Ok) return Flow::Fatal;
  }
}

auto Uploader::Run::probe() -> Flow {
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
  if (answers_as_lsc6()) {
    return fatal(UploadStatus::OtherDialect,
                 "the board on " + link().transport().describe() +
                     " ignores GetBatteryVoltage and answers a DownloadAction with 55 55 02 19: "
                     "it speaks the " +
                     std::string(kLsc6Dialect.name) + " dialect");
  }
  return fatal(UploadStatus::NoAnswer,
               "no reply from a controller on " + link().transport().describe() + " (asked " +
                   std::to_string(max_attempts()) + " times for its battery voltage, waiting " +
                   seconds_text(timeout) +
                   " each time); check the port, the cable and that the controller is "
                   "switched on");
}

bool Uploader::Run::answers_as_lsc6() {
  if (link().interrupted()) return false;
  return lsc6_answers(link().transport(), clock(), nullptr, opt().group,
                      up_.reply_timeout(0, 0, false));
}

// GroupRun, then a barrier so a refusal to start or a notification can be seen.
void Uploader::Run::start_group() {
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
  const Flow f = started.status == WaitStatus::Interrupted ? fatal(UploadStatus::Interrupted, "")
                                                           : barrier(Barrier::Sync, 0);
  if (fail_ && fail_->status == UploadStatus::Interrupted) {
    // Ctrl-C while the group was starting: the group is stored, but the robot must not move.
    fail_->message = "interrupted after starting group " + std::to_string(opt().group);
    return;
  }
  if (f != Flow::Ok) {
    note("the controller did not answer after GroupRun: " + (fail_ ? fail_->message : ""));
    fail_.reset();
  }
}

void Uploader::Run::finish(Flow flow) {
  if (fail_ && fail_->status == UploadStatus::Interrupted) secure_after_interrupt();
  if (flow == Flow::Ok && completed_ && !fail_) {
    result_.status = UploadStatus::Completed;
    result_.group_state = GroupState::Stored;
    result_.actions_acknowledged = actions_done_;
    return;
  }
  result_.status = fail_ ? fail_->status : UploadStatus::LinkError;
  result_.message = fail_ ? fail_->message : "the upload ended unexpectedly";
  result_.actions_acknowledged = actions_done_;
  if (completed_) {
    result_.group_state = GroupState::Stored;
  } else if (committed_unconfirmed_) {
    result_.group_state = GroupState::Uncertain;
  } else if (erased_) {
    result_.group_state = GroupState::Empty;
  } else if (step1_unanswered_) {
    result_.group_state = GroupState::MaybeErased;
  } else {
    result_.group_state = GroupState::Unchanged;
  }
}

UploadResult Uploader::upload(const std::vector<PlannedFrame>& plan) {
  Run run(*this, plan);
  return run.go();
}

UploadResult Uploader::upload(const std::vector<lsc::Request>& plan) {
  auto frames = plan_frames(plan);
  if (!frames) {
    UploadResult result;
    result.status = UploadStatus::BadPlan;
    result.message = "cannot encode the download plan: " + frames.error().message;
    return result;
  }
  return upload(*frames);
}

}  // namespace seqc::upload
