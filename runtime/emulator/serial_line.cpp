#include "runtime/emulator/serial_line.hpp"

#include <algorithm>

#include "protocol/lsc/lsc_frame.hpp"

namespace seqc::emu {

void RequestFramer::reset() {
  last_at_.reset();
  garbage_.clear();
  frame_.clear();
}

void RequestFramer::flush_garbage(std::vector<Piece>& out) {
  if (garbage_.empty()) return;
  out.push_back(Piece{std::move(garbage_), false});
  garbage_.clear();
}

void RequestFramer::feed(ByteView bytes, io::TimePoint at, std::vector<Piece>& out) {
  if (bytes.empty()) return;
  if (gap_ > io::Duration{0} && last_at_ && at - *last_at_ > gap_ && !frame_.empty()) {
    // An idle line: whatever frame was in progress will never complete.
    flush_garbage(out);
    out.push_back(Piece{std::move(frame_), false});
    frame_.clear();
  }
  last_at_ = at;
  for (std::uint8_t b : bytes) {
    if (frame_.size() < 2) {
      if (b == lsc::kHeaderByte) {
        frame_.push_back(b);
      } else {
        // A lone 55 followed by something else was garbage after all.
        garbage_.insert(garbage_.end(), frame_.begin(), frame_.end());
        frame_.clear();
        garbage_.push_back(b);
      }
      continue;
    }
    frame_.push_back(b);
    if (frame_.size() == 3) {
      flush_garbage(out);
      if (b < lsc::kMinLen) {
        out.push_back(Piece{std::move(frame_), false});
        frame_.clear();
      }
      continue;
    }
    if (frame_.size() == 2u + frame_[2]) {
      out.push_back(Piece{std::move(frame_), true});
      frame_.clear();
    }
  }
  // Garbage is reported as soon as it is known to be garbage; a trailing 55 may still start
  // a header and stays in frame_.
  flush_garbage(out);
}

InputLine::InputLine(std::uint32_t baud)
    : byte_time_(baud == 0 ? io::Duration{0} : io::Duration{10'000'000'000LL / baud}) {}

io::TimePoint InputLine::push(ByteView bytes, io::TimePoint at) {
  io::TimePoint t = at;
  for (std::uint8_t b : bytes) {
    t = (last_delivery_ ? std::max(at, *last_delivery_) : at) + byte_time_;
    last_delivery_ = t;
    queue_.push_back(Byte{t, b});
  }
  return t;
}

std::optional<io::TimePoint> InputLine::next_delivery_at() const {
  if (empty()) return std::nullopt;
  return queue_[head_].at;
}

std::vector<InputLine::Arrival> InputLine::take(io::TimePoint upto) {
  std::vector<Arrival> out;
  for (; head_ < queue_.size() && queue_[head_].at <= upto; ++head_) {
    const Byte& b = queue_[head_];
    if (out.empty() || out.back().at != b.at) out.push_back(Arrival{b.at, {}});
    out.back().bytes.push_back(b.value);
  }
  // Compact once everything queued so far has been delivered (the usual case after a frame).
  if (empty()) {
    queue_.clear();
    head_ = 0;
  }
  return out;
}

void InputLine::clear() {
  queue_.clear();
  head_ = 0;
}

OutputLine::OutputLine(std::uint32_t baud)
    : byte_time_(baud == 0 ? io::Duration{0} : io::Duration{10'000'000'000LL / baud}) {}

void OutputLine::send(Bytes bytes, io::TimePoint ready) {
  if (bytes.empty()) return;
  Message m{ready, seq_++, std::move(bytes)};
  // A message already on the wire keeps its place at the front.
  auto first = queue_.begin() + (front_sent_ > 0 ? 1 : 0);
  auto pos = std::upper_bound(first, queue_.end(), m, [](const Message& a, const Message& b) {
    return a.ready < b.ready || (a.ready == b.ready && a.seq < b.seq);
  });
  queue_.insert(pos, std::move(m));
}

io::TimePoint OutputLine::start_of_front() const {
  if (front_sent_ > 0) return front_start_;
  return std::max(queue_.front().ready, line_free_);
}

std::optional<io::TimePoint> OutputLine::next_byte_at() const {
  if (queue_.empty()) return std::nullopt;
  return start_of_front() + byte_time_ * static_cast<std::int64_t>(front_sent_ + 1);
}

std::optional<io::TimePoint> OutputLine::front_last_byte_at() const {
  if (queue_.empty()) return std::nullopt;
  return start_of_front() + byte_time_ * static_cast<std::int64_t>(queue_.front().bytes.size());
}

Bytes OutputLine::take(io::TimePoint upto) {
  Bytes out;
  while (!queue_.empty()) {
    const io::TimePoint start = start_of_front();
    Message& m = queue_.front();
    while (front_sent_ < m.bytes.size() &&
           start + byte_time_ * static_cast<std::int64_t>(front_sent_ + 1) <= upto) {
      out.push_back(m.bytes[front_sent_++]);
    }
    if (front_sent_ < m.bytes.size()) {
      if (front_sent_ > 0) front_start_ = start;
      break;
    }
    line_free_ = start + byte_time_ * static_cast<std::int64_t>(m.bytes.size());
    queue_.erase(queue_.begin());
    front_sent_ = 0;
  }
  return out;
}

void OutputLine::clear() {
  queue_.clear();
  front_sent_ = 0;
}

}  // namespace seqc::emu
