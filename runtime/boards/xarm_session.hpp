// A conversation with an xArm-family controller for one command: ask for a reply of a given
// type, tell it something and confirm it was heard (a GetBatteryVoltage round trip, since most
// commands have no reply of their own), and keep the notifications the controller sends
// unasked (GroupStarted, GroupStopped) for the caller to look at. The session is the link's
// observer while it lives. It has no words: the first failure is kept as an Outcome, which the
// CLI turns into a sentence and an exit code.
//
// Failures, as Outcome fields: SendFailed (request = lsc::describe of it, detail = the link's
// words); NoReply from ask (awaiting = what was awaited); Unconfirmed from tell and confirm
// (request, attempts); HangUp and ReadFailed (detail); Interrupted (awaiting is empty when the
// flag was up before anything was sent, else what was awaited). The session never sleeps or
// reads the wall clock: all waiting is the link's, on its clock.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "runtime/boards/board.hpp"
#include "runtime/io/clock.hpp"
#include "protocol/lsc/lsc_messages.hpp"
#include "runtime/upload/controller_link.hpp"

namespace seqc::boards {

class XarmSession final : private upload::LinkObserver {
 public:
  XarmSession(upload::ControllerLink& link, io::Duration timeout);  // becomes the link's observer
  ~XarmSession() override;
  XarmSession(const XarmSession&) = delete;
  XarmSession& operator=(const XarmSession&) = delete;

  // Sends `request` and waits for a reply of type R; nullopt after a failure (see failure()).
  template <class R>
  std::optional<R> ask(const lsc::Request& request, const std::string& awaiting);
  bool tell(const lsc::Request& request);    // send, then confirm(request)
  bool confirm(const std::string& request);  // GetBatteryVoltage, at most kConfirmAttempts times

  const std::vector<lsc::Reply>& notifications() const { return notifications_; }
  const std::optional<Outcome>& failure() const { return failure_; }
  upload::ControllerLink& link() { return link_; }
  io::Duration timeout() const { return timeout_; }

  static constexpr int kConfirmAttempts = 2;

 private:
  void on_notification(const lsc::Reply& reply) override { notifications_.push_back(reply); }
  std::optional<lsc::Reply> exchange(const lsc::Request& request,
                                     const std::function<bool(const lsc::Reply&)>& want,
                                     const std::string& awaiting);
  // Drains, sends, waits up to the timeout for a reply `want` takes.
  upload::WaitResult round_trip(const lsc::Request& request,
                                const std::function<bool(const lsc::Reply&)>& want);
  void fail_wait(const upload::WaitResult& result, const std::string& request,
                 const std::string& awaiting);
  bool send(const lsc::Request& request);
  void fail(Outcome outcome);

  upload::ControllerLink& link_;
  io::Duration timeout_;
  std::vector<lsc::Reply> notifications_;
  std::optional<Outcome> failure_;
};

template <class R>
std::optional<R> XarmSession::ask(const lsc::Request& request, const std::string& awaiting) {
  auto reply = exchange(
      request, [](const lsc::Reply& r) { return std::holds_alternative<R>(r); }, awaiting);
  if (!reply) return std::nullopt;
  return std::get<R>(*reply);
}

}  // namespace seqc::boards
