#include "runtime/upload/controller_link.hpp"

#include <utility>
#include <variant>

namespace seqc::upload {

bool is_notification(const lsc::Reply& reply) {
  return std::holds_alternative<lsc::GroupStarted>(reply) ||
         std::holds_alternative<lsc::GroupStopped>(reply) ||
         std::holds_alternative<lsc::GroupFinished>(reply);
}

void ControllerLink::set_observer(LinkObserver* observer) {
  observer_ = observer;
  set_frame_observer(observer);
}

Status ControllerLink::send(const lsc::Request& request) {
  auto bytes = lsc::encode_serial(request);
  if (!bytes) return bytes.error();
  return send_bytes(*bytes);
}

void ControllerLink::report_skipped(const lsc::Reply& reply) {
  if (observer_ == nullptr) return;
  if (is_notification(reply)) {
    observer_->on_notification(reply);
  } else {
    observer_->on_unexpected(reply);
  }
}

WaitResult ControllerLink::wait_for(const ReplyPredicate& accept, io::TimePoint deadline,
                                    OnInterrupt on_interrupt) {
  WaitResult result;
  const FrameWait w = wait_frames(
      [&](const lsc::Frame& frame) -> Result<bool> {
        auto reply = lsc::decode_reply(frame);
        if (!reply) return reply.error();
        const Verdict v = accept(*reply);
        if (v == Verdict::Take) {
          result.reply = std::move(reply).value();
          return true;
        }
        if (v == Verdict::Skip) report_skipped(*reply);
        return false;
      },
      deadline, on_interrupt);
  result.status = w.status;
  result.message =
      w.status == WaitStatus::HangUp && w.message.empty() ? "the device went away" : w.message;
  return result;
}

WaitStatus ControllerLink::drain(const std::function<void(const lsc::Reply&)>& seen) {
  return drain_frames([&](const lsc::Frame& frame) -> Result<bool> {
    auto reply = lsc::decode_reply(frame);
    if (!reply) return reply.error();
    if (is_notification(*reply)) {
      report_skipped(*reply);
    } else {
      seen(*reply);
    }
    return false;
  });
}

}  // namespace seqc::upload
