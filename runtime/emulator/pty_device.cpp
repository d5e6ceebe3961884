#include "runtime/emulator/pty_device.hpp"

#include <algorithm>

namespace seqc::emu {

void XArmPtyDevice::receive(ByteView bytes, io::TimePoint at) {
  if (emu_.hung_up()) return;
  input_.push(bytes, at);
  deliver(at);  // unpaced (baud 0): at once
}

void XArmPtyDevice::deliver(io::TimePoint upto) {
  for (const InputLine::Arrival& a : input_.take(upto)) {
    if (emu_.hung_up()) break;
    emu_.receive(a.bytes, a.at);
  }
  if (emu_.hung_up()) input_.clear();
}

std::optional<io::TimePoint> XArmPtyDevice::next_output_at() const {
  std::optional<io::TimePoint> next = emu_.next_output_at();
  if (auto in = input_.next_delivery_at(); in && (!next || *in < *next)) next = in;
  return next;
}

Bytes XArmPtyDevice::take_output(io::TimePoint upto) {
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
