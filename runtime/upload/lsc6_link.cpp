#include "runtime/upload/lsc6_link.hpp"

#include <algorithm>
#include <array>

#include "protocol/lsc_messages.hpp"

namespace seqc::upload {
namespace {

constexpr io::Duration kSlice = std::chrono::milliseconds(100);

}  // namespace

Lsc6Link::Lsc6Link(io::Transport& transport, io::Clock& clock, const std::atomic<bool>* interrupted)
    : transport_(transport), clock_(clock), interrupted_(interrupted) {}

Status Lsc6Link::send(const lsc6::Request& request) {
  auto bytes = lsc6::encode_serial(request);
  if (!bytes) return bytes.error();
  return send_bytes(*bytes);
}

Status Lsc6Link::send_bytes(ByteView bytes) {
  auto status = transport_.write(bytes);
  if (status) {
    ++stats_.frames_sent;
    stats_.bytes_sent += bytes.size();
  }
  return status;
}

LinkStats Lsc6Link::stats() const {
  LinkStats s = stats_;
  s.garbage_bytes = decoder_.skipped_bytes();
  return s;
}

std::optional<lsc6::Reply> Lsc6Link::next_answer() {
  while (auto frame = decoder_.next()) {
    ++stats_.frames_received;
    auto reply = lsc6::decode_reply(*frame);
    if (!reply) {
      auto other = lsc::decode_reply(*frame);
      if (other && std::holds_alternative<lsc::BatteryVoltage>(*other)) ++other_dialect_;
      ++skipped_;  // not an answer this firmware sends
      continue;
    }
    if (std::holds_alternative<lsc6::GroupFinished>(*reply)) ++finished_;
    return std::move(reply).value();
  }
  return std::nullopt;
}

io::ReadResult Lsc6Link::read_some(io::TimePoint deadline) {
  std::array<std::uint8_t, 256> buffer{};
  io::ReadResult r = transport_.read(buffer, deadline);
  if (r.status == io::ReadStatus::Data) {
    const std::size_t n = std::min(r.count, buffer.size());
    stats_.bytes_received += n;
    decoder_.feed(ByteView(buffer.data(), n));
  }
  return r;
}

Lsc6Wait Lsc6Link::wait_for(const std::function<bool(const lsc6::Reply&)>& take,
                            io::TimePoint deadline) {
  for (;;) {
    while (auto reply = next_answer()) {
      if (take(*reply)) return Lsc6Wait{WaitStatus::Matched, *reply, {}};
      if (!std::holds_alternative<lsc6::GroupFinished>(*reply)) ++skipped_;
    }
    if (interrupted()) return Lsc6Wait{WaitStatus::Interrupted, {}, "interrupted"};
    const io::TimePoint now = clock_.now();
    if (now >= deadline) return Lsc6Wait{WaitStatus::Timeout, {}, {}};
    const io::ReadResult r = read_some(std::min(deadline, now + kSlice));
    if (r.status == io::ReadStatus::HangUp) return Lsc6Wait{WaitStatus::HangUp, {}, r.message};
    if (r.status == io::ReadStatus::Error) return Lsc6Wait{WaitStatus::Error, {}, r.message};
  }
}

std::vector<lsc6::Reply> Lsc6Link::drain(WaitStatus& status) {
  status = WaitStatus::Timeout;
  std::vector<lsc6::Reply> out;
  for (;;) {
    while (auto reply = next_answer()) out.push_back(*reply);
    const io::ReadResult r = read_some(clock_.now());
    if (r.status == io::ReadStatus::Data) continue;
    if (r.status == io::ReadStatus::HangUp) status = WaitStatus::HangUp;
    if (r.status == io::ReadStatus::Error) status = WaitStatus::Error;
    return out;
  }
}

void Lsc6Link::discard_input() {
  decoder_.reset();
  transport_.discard_input();
}

}  // namespace seqc::upload
