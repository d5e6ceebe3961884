#include "runtime/upload/controller_link.hpp"

#include <algorithm>
#include <array>
#include <variant>

namespace seqc::upload {

const char* to_string(WaitStatus status) {
  switch (status) {
    case WaitStatus::Matched:
      return "matched";
    case WaitStatus::Timeout:
      return "timeout";
    case WaitStatus::HangUp:
      return "hang-up";
    case WaitStatus::Interrupted:
      return "interrupted";
    case WaitStatus::Error:
      return "error";
  }
  return "?";
}

bool is_notification(const lsc::Reply& reply) {
  return std::holds_alternative<lsc::GroupStarted>(reply) ||
         std::holds_alternative<lsc::GroupStopped>(reply) ||
         std::holds_alternative<lsc::GroupFinished>(reply);
}

ControllerLink::ControllerLink(io::Transport& transport, io::Clock& clock,
                               const std::atomic<bool>* interrupted)
    : transport_(transport), clock_(clock), interrupted_(interrupted) {}

Status ControllerLink::send(const lsc::Request& request) {
  auto bytes = lsc::encode_serial(request);
  if (!bytes) return bytes.error();
  return send_bytes(*bytes);
}

Status ControllerLink::send_bytes(ByteView bytes) {
  auto status = transport_.write(bytes);
  if (status) {
    ++stats_.frames_sent;
    stats_.bytes_sent += bytes.size();
  }
  return status;
}

LinkStats ControllerLink::stats() const {
  LinkStats s = stats_;
  s.garbage_bytes = decoder_.skipped_bytes() + dropped_partial_;
  return s;
}

void ControllerLink::report_skipped(const lsc::Reply& reply) {
  if (observer_ == nullptr) return;
  if (is_notification(reply)) {
    observer_->on_notification(reply);
  } else {
    observer_->on_unexpected(reply);
  }
}

std::optional<lsc::Reply> ControllerLink::next_reply() {
  while (auto frame = decoder_.next()) {
    ++stats_.frames_received;
    auto reply = lsc::decode_reply(*frame);
    if (reply) return std::move(reply).value();
    if (observer_ != nullptr) observer_->on_unparsed(*frame, reply.error().message);
  }
  return std::nullopt;
}

io::ReadResult ControllerLink::read_some(io::TimePoint deadline) {
  std::array<std::uint8_t, 256> buffer{};
  io::ReadResult r = transport_.read(buffer, deadline);
  if (r.status == io::ReadStatus::Data) {
    const std::size_t n = std::min(r.count, buffer.size());
    stats_.bytes_received += n;
    decoder_.feed(ByteView(buffer.data(), n));
  }
  return r;
}

WaitResult ControllerLink::wait_for(const ReplyPredicate& accept, io::TimePoint deadline,
                                    OnInterrupt on_interrupt) {
  WaitResult result;
  for (;;) {
    while (auto reply = next_reply()) {
      const Verdict v = accept(*reply);
      if (v == Verdict::Take) {
        result.status = WaitStatus::Matched;
        result.reply = std::move(*reply);
        return result;
      }
      if (v == Verdict::Skip) report_skipped(*reply);
    }
    if (on_interrupt == OnInterrupt::Stop && interrupted()) {
      result.status = WaitStatus::Interrupted;
      return result;
    }
    const io::TimePoint now = clock_.now();
    if (now >= deadline) {
      result.status = WaitStatus::Timeout;
      return result;
    }
    const io::TimePoint slice_end = std::min(deadline, now + slice_);
    io::ReadResult r = read_some(slice_end);
    switch (r.status) {
      case io::ReadStatus::Data:
        break;
      case io::ReadStatus::Timeout:
        // A transport that gives up early must not make this loop spin on a manual clock.
        if (clock_.now() < slice_end) clock_.sleep_until(slice_end);
        break;
      case io::ReadStatus::HangUp:
        result.status = WaitStatus::HangUp;
        result.message = r.message.empty() ? "the device went away" : r.message;
        return result;
      case io::ReadStatus::Error:
        result.status = WaitStatus::Error;
        result.message = r.message;
        return result;
    }
  }
}

WaitStatus ControllerLink::drain(const std::function<void(const lsc::Reply&)>& seen) {
  for (;;) {
    while (auto reply = next_reply()) {
      if (is_notification(*reply)) {
        report_skipped(*reply);
      } else {
        seen(*reply);
      }
    }
    io::ReadResult r = read_some(clock_.now());
    if (r.status == io::ReadStatus::Data) continue;
    if (r.status == io::ReadStatus::HangUp) return WaitStatus::HangUp;
    if (r.status == io::ReadStatus::Error) return WaitStatus::Error;
    return WaitStatus::Timeout;
  }
}

std::size_t ControllerLink::drop_partial_frame() {
  const std::size_t n = decoder_.pending_bytes();
  if (n > 0) {
    dropped_partial_ += n;
    decoder_.reset();
  }
  return n;
}

void ControllerLink::discard_input() {
  decoder_.reset();
  transport_.discard_input();
}

bool ControllerLink::reopen(io::TimePoint deadline) {
  decoder_.reset();
  // In slices, so Ctrl-C ends the wait as it ends any other.
  for (;;) {
    if (interrupted()) return false;
    const io::TimePoint now = clock_.now();
    if (now >= deadline) return false;
    if (transport_.reopen(std::min(deadline, now + slice_))) break;
    if (clock_.now() == now) return false;  // it did not even wait: it cannot reconnect
  }
  transport_.discard_input();
  return true;
}

}  // namespace seqc::upload
