#include "runtime/upload/lsc6_link.hpp"

#include <utility>
#include <variant>

#include "protocol/lsc/lsc_messages.hpp"

namespace seqc::upload {

Status Lsc6Link::send(const lsc6::Request& request) {
  auto bytes = lsc6::encode_serial(request);
  if (!bytes) return bytes.error();
  return send_bytes(*bytes);
}

Result<lsc6::Reply> Lsc6Link::answer(const lsc::Frame& frame) {
  auto reply = lsc6::decode_reply(frame);
  if (!reply) {
    auto other = lsc::decode_reply(frame);
    if (other && std::holds_alternative<lsc::BatteryVoltage>(*other)) ++other_dialect_;
    ++skipped_;  // not an answer this firmware sends
    return reply;
  }
  if (std::holds_alternative<lsc6::GroupFinished>(*reply)) ++finished_;
  return reply;
}

Lsc6Wait Lsc6Link::wait_for(const std::function<bool(const lsc6::Reply&)>& take,
                            io::TimePoint deadline) {
  Lsc6Wait result;
  const FrameWait w = wait_frames(
      [&](const lsc::Frame& frame) -> Result<bool> {
        auto reply = answer(frame);
        if (!reply) return reply.error();
        if (take(*reply)) {
          result.reply = std::move(reply).value();
          return true;
        }
        if (!std::holds_alternative<lsc6::GroupFinished>(*reply)) ++skipped_;
        return false;
      },
      deadline);
  result.status = w.status;
  result.message = w.status == WaitStatus::Interrupted ? "interrupted" : w.message;
  return result;
}

std::vector<lsc6::Reply> Lsc6Link::drain(WaitStatus& status) {
  std::vector<lsc6::Reply> out;
  status = drain_frames([&](const lsc::Frame& frame) -> Result<bool> {
    auto reply = answer(frame);
    if (!reply) return reply.error();
    out.push_back(std::move(reply).value());
    return false;
  });
  return out;
}

}  // namespace seqc::upload
