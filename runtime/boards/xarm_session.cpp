#include "runtime/boards/xarm_session.hpp"

#include <utility>

namespace seqc::boards {

XarmSession::XarmSession(upload::ControllerLink& link, io::Duration timeout)
    : link_(link), timeout_(timeout) {
  link_.set_observer(this);
}

XarmSession::~XarmSession() { link_.set_observer(nullptr); }

void XarmSession::fail(Outcome outcome) {
  if (!failure_) failure_ = std::move(outcome);
}

bool XarmSession::send(const lsc::Request& request) {
  if (failure_) return false;
  if (link_.interrupted()) {
    fail(Outcome{Failure::Interrupted, lsc::describe(request), "", "", 0});
    return false;
  }
  if (auto sent = link_.send(request); !sent) {
    fail(Outcome{Failure::SendFailed, lsc::describe(request), "", sent.error().message, 0});
    return false;
  }
  return true;
}

upload::WaitResult XarmSession::round_trip(const lsc::Request& request,
                                           const std::function<bool(const lsc::Reply&)>& want) {
  upload::WaitResult r;
  r.status = upload::WaitStatus::Error;
  // Replies nobody waits for any more (a late answer) must not be taken for the answer to this
  // request. Notifications are kept (on_notification) for the command to report.
  link_.drain([](const lsc::Reply&) {});
  if (!send(request)) return r;
  const io::TimePoint deadline = link_.clock().now() + timeout_;
  return link_.wait_for(
      [&](const lsc::Reply& reply) {
        // Skipped notifications reach on_notification through the link.
        return want(reply) ? upload::Verdict::Take : upload::Verdict::Skip;
      },
      deadline);
}

void XarmSession::fail_wait(const upload::WaitResult& r, const std::string& request,
                            const std::string& awaiting) {
  switch (r.status) {
    case upload::WaitStatus::Matched:
      return;
    case upload::WaitStatus::Timeout:
      fail(Outcome{Failure::NoReply, request, awaiting, "", 0});
      return;
    case upload::WaitStatus::HangUp:
      fail(Outcome{Failure::HangUp, request, awaiting, r.message, 0});
      return;
    case upload::WaitStatus::Interrupted:
      fail(Outcome{Failure::Interrupted, request, awaiting, "", 0});
      return;
    case upload::WaitStatus::Error:
      // A send failure has already been kept; this is a read failure.
      fail(Outcome{Failure::ReadFailed, request, awaiting, r.message, 0});
      return;
  }
}

std::optional<lsc::Reply> XarmSession::exchange(const lsc::Request& request,
                                                const std::function<bool(const lsc::Reply&)>& want,
                                                const std::string& awaiting) {
  if (failure_) return std::nullopt;
  upload::WaitResult r = round_trip(request, want);
  if (r.ok()) return std::move(r.reply);
  fail_wait(r, lsc::describe(request), awaiting);
  return std::nullopt;
}

bool XarmSession::tell(const lsc::Request& request) {
  if (failure_ || !send(request)) return false;
  return confirm(lsc::describe(request));
}

bool XarmSession::confirm(const std::string& request) {
  if (failure_) return false;
  // The controller answers in the order it receives, so the battery voltage shows the request
  // arrived before it. A controller still busy with the request may drop the first check.
  const auto is_battery = [](const lsc::Reply& r) {
    return std::holds_alternative<lsc::BatteryVoltage>(r);
  };
  upload::WaitResult r;
  for (int attempt = 0; attempt < kConfirmAttempts && !failure_; ++attempt) {
    r = round_trip(lsc::GetBatteryVoltage{}, is_battery);
    if (r.ok()) return true;
    if (r.status != upload::WaitStatus::Timeout) break;
  }
  if (r.status == upload::WaitStatus::Timeout && !failure_) {
    fail(Outcome{Failure::Unconfirmed, request, "", "", kConfirmAttempts});
  } else {
    fail_wait(r, request, "confirming " + request);
  }
  return false;
}

}  // namespace seqc::boards
