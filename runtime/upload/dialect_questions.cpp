#include "runtime/upload/dialect_questions.hpp"

#include <cmath>
#include <variant>

#include "protocol/lsc/lsc_messages.hpp"
#include "protocol/lsc6/lsc6_messages.hpp"
#include "runtime/upload/frame_link.hpp"
#include "runtime/upload/lsc6_link.hpp"

namespace seqc::upload {
namespace {

// Both frames on the wire at the link's rate, plus the margin.
io::Duration wait_for_reply(const io::Transport& transport, std::size_t frame_bytes,
                            std::size_t reply_bytes, io::Duration margin) {
  const double wire = static_cast<double>(frame_bytes + reply_bytes) * transport.seconds_per_byte();
  return io::Duration(static_cast<long long>(std::ceil(wire * 1e9))) + margin;
}

}  // namespace

bool lsc6_answers(io::Transport& transport, io::Clock& clock, const std::atomic<bool>* interrupted,
                  std::uint8_t group, io::Duration margin) {
  if (transport.max_frame_bytes() != 0) return false;
  Lsc6Link link(transport, clock, interrupted);
  if (link.interrupted()) return false;
  // 55 55 LEN 19 G TOTAL IDX N tLo tHi. lsc6::encode refuses an index not below the total,
  // which is the point here, so the frame is put together from its fields.
  const lsc::Frame frame{static_cast<std::uint8_t>(lsc6::Command::DownloadAction),
                         Bytes{group, 1, 255, 0, 0, 0}};
  const Bytes request = lsc::encode_serial(frame).value();
  if (!link.send_bytes(request)) return false;
  const Lsc6Wait w = link.wait_for(
      [](const lsc6::Reply& r) { return std::holds_alternative<lsc6::ActionStored>(r); },
      clock.now() + wait_for_reply(transport, request.size(), 4, margin));
  return w.ok();
}

bool xarm_answers(io::Transport& transport, io::Clock& clock, const std::atomic<bool>* interrupted,
                  io::Duration margin) {
  FrameLink link(transport, clock, interrupted);
  if (link.interrupted()) return false;
  const Bytes request = lsc::encode_serial(lsc::Request{lsc::GetBatteryVoltage{}}).value();
  if (!link.send_bytes(request)) return false;
  const FrameWait w = link.wait_frames(
      [](const lsc::Frame& frame) -> Result<bool> {
        auto reply = lsc::decode_reply(frame);
        return reply && std::holds_alternative<lsc::BatteryVoltage>(*reply);
      },
      clock.now() + wait_for_reply(transport, request.size(), 6, margin));
  return w.status == WaitStatus::Matched;
}

}  // namespace seqc::upload
