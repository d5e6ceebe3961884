#include "runtime/emulator/pty_device.hpp"

namespace seqc::emu {

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
