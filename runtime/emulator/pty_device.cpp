#include "runtime/emulator/pty_device.hpp"

#include <algorithm>

namespace seqc::emu {

ControllerPtyDevice::ControllerPtyDevice(ControllerDevice& emu)
    : emu_(emu), input_(emu.baud()), framer_(emu.frame_gap()) {}

bool ControllerPtyDevice::reconnect(io::TimePoint at) {
  if (!emu_.reconnect(at)) return false;
  input_.clear();
  framer_.reset();
  frame_ends_.clear();
  last_arrival_.reset();
  return true;
}

void ControllerPtyDevice::receive(ByteView bytes, io::TimePoint at) {
  if (emu_.hung_up() || bytes.empty()) return;
  std::vector<RequestFramer::Piece> pieces;
  for (std::uint8_t b : bytes) {
    const io::TimePoint t = input_.push(ByteView(&b, 1), at);
    framer_.feed(ByteView(&b, 1), t, pieces);
    for (const auto& piece : pieces) {
      if (piece.framed) frame_ends_.push_back(t);
    }
    pieces.clear();
    last_arrival_ = t;
  }
  deliver(at);  // unpaced (baud 0): at once
}

void ControllerPtyDevice::deliver(io::TimePoint upto) {
  for (const InputLine::Arrival& a : input_.take(upto)) {
    if (emu_.hung_up()) break;
    emu_.receive(a.bytes, a.at);
  }
  frame_ends_.erase(frame_ends_.begin(),
                    std::upper_bound(frame_ends_.begin(), frame_ends_.end(), upto));
  if (emu_.hung_up()) {
    input_.clear();
    frame_ends_.clear();
  }
  if (input_.empty()) last_arrival_.reset();
}

std::optional<io::TimePoint> ControllerPtyDevice::next_output_at() const {
  std::optional<io::TimePoint> next = emu_.next_message_end_at();
  auto earliest = [&next](std::optional<io::TimePoint> t) {
    if (t && (!next || *t < *next)) next = t;
  };
  if (!frame_ends_.empty()) earliest(frame_ends_.front());
  earliest(last_arrival_);
  return next;
}

Bytes ControllerPtyDevice::take_output(io::TimePoint upto) {
  deliver(upto);
  return emu_.take_output(upto);
}

void RaspblockPtyDevice::receive(ByteView bytes, io::TimePoint at) {
  emu_.receive(bytes, at);
  if (!log_) return;
  const auto& timeline = emu_.timeline();
  for (; printed_ < timeline.size(); ++printed_)
    *log_ << describe_change(timeline[printed_]) << '\n';
  const auto& rejections = emu_.rejections();
  for (; rejections_printed_ < rejections.size(); ++rejections_printed_) {
    *log_ << "rejected: " << rejections[rejections_printed_].reason << '\n';
  }
  log_->flush();
}

}  // namespace seqc::emu
