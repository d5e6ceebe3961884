#include "runtime/upload/frame_link.hpp"

#include <algorithm>
#include <array>

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

FrameLink::FrameLink(io::Transport& transport, io::Clock& clock,
                     const std::atomic<bool>* interrupted)
    : transport_(transport), clock_(clock), interrupted_(interrupted) {}

Status FrameLink::send_bytes(ByteView bytes) {
  auto status = transport_.write(bytes);
  if (status) {
    ++stats_.frames_sent;
    stats_.bytes_sent += bytes.size();
  }
  return status;
}

LinkStats FrameLink::stats() const {
  LinkStats s = stats_;
  s.garbage_bytes = decoder_.skipped_bytes() + dropped_partial_;
  return s;
}

bool FrameLink::take_buffered(const OnFrame& on_frame) {
  while (auto frame = decoder_.next()) {
    ++stats_.frames_received;
    const Result<bool> taken = on_frame(*frame);
    if (!taken) {
      if (frame_observer_ != nullptr) frame_observer_->on_unparsed(*frame, taken.error().message);
      continue;
    }
    if (*taken) return true;
  }
  return false;
}

io::ReadResult FrameLink::read_some(io::TimePoint deadline) {
  std::array<std::uint8_t, 256> buffer{};
  io::ReadResult r = transport_.read(buffer, deadline);
  if (r.status == io::ReadStatus::Data) {
    const std::size_t n = std::min(r.count, buffer.size());
    stats_.bytes_received += n;
    decoder_.feed(ByteView(buffer.data(), n));
  }
  return r;
}

FrameWait FrameLink::wait_frames(const OnFrame& on_frame, io::TimePoint deadline,
                                 OnInterrupt on_interrupt) {
  for (;;) {
    if (take_buffered(on_frame)) return {WaitStatus::Matched, {}};
    if (on_interrupt == OnInterrupt::Stop && interrupted()) return {WaitStatus::Interrupted, {}};
    const io::TimePoint now = clock_.now();
    if (now >= deadline) return {WaitStatus::Timeout, {}};
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
        return {WaitStatus::HangUp, r.message};
      case io::ReadStatus::Error:
        return {WaitStatus::Error, r.message};
    }
  }
}

WaitStatus FrameLink::drain_frames(const OnFrame& on_frame) {
  for (;;) {
    while (take_buffered(on_frame)) {
    }
    io::ReadResult r = read_some(clock_.now());
    if (r.status == io::ReadStatus::Data) continue;
    if (r.status == io::ReadStatus::HangUp) return WaitStatus::HangUp;
    if (r.status == io::ReadStatus::Error) return WaitStatus::Error;
    return WaitStatus::Timeout;
  }
}

std::size_t FrameLink::drop_partial_frame() {
  const std::size_t n = decoder_.pending_bytes();
  if (n > 0) {
    dropped_partial_ += n;
    decoder_.reset();
  }
  return n;
}

void FrameLink::discard_input() {
  decoder_.reset();
  transport_.discard_input();
}

bool FrameLink::reopen(io::TimePoint deadline) {
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
