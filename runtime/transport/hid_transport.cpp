#include "runtime/transport/hid_transport.hpp"

#include <algorithm>
#include <array>
#include <climits>
#include <cstring>

#include "protocol/lsc/lsc_frame.hpp"

namespace seqc::transport {
namespace {

int timeout_ms(io::Duration remaining) {
  if (remaining <= io::Duration::zero()) return 0;
  auto ms = std::chrono::ceil<std::chrono::milliseconds>(remaining).count();
  return static_cast<int>(std::min<decltype(ms)>(ms, INT_MAX));
}

// An input report that is not a frame is passed on as raw bytes, without its zero padding:
// the caller's frame decoder skips garbage and resynchronises on 55 55, and a dump of the
// session still shows what the device sent.
Bytes undecodable_report(ByteView report) {
  std::size_t end = report.size();
  while (end > 0 && report[end - 1] == 0) --end;
  return Bytes(report.begin(), report.begin() + static_cast<std::ptrdiff_t>(end));
}

}  // namespace

HidTransport::HidTransport(std::unique_ptr<HidDevice> device, io::Clock& clock,
                           std::string description, HidReconnect reconnect)
    : device_(std::move(device)),
      clock_(clock),
      description_(std::move(description)),
      reconnect_(std::move(reconnect)) {}

bool HidTransport::reopen(io::TimePoint deadline) {
  if (!reconnect_.backend) return false;
  for (;;) {
    if (reopen_once()) return true;
    const io::TimePoint now = clock_.now();
    if (now >= deadline) return false;
    clock_.sleep_until(std::min(deadline, now + kReopenPoll));
  }
}

bool HidTransport::is_same_device(const HidDeviceInfo& info) const {
  const HidDeviceInfo& was = reconnect_.device;
  if (!was.serial_number.empty()) return info.serial_number == was.serial_number;
  return info.path == was.path;
}

bool HidTransport::reopen_once() {
  auto found = find_lobot_devices(*reconnect_.backend);
  if (!found) return false;
  const auto same = std::find_if(found->begin(), found->end(),
                                 [&](const HidDeviceInfo& d) { return is_same_device(d); });
  if (same == found->end()) return false;  // not back yet, or another controller
  auto device = reconnect_.backend->open(same->path);
  if (!device) return false;
  device_ = std::move(*device);
  pending_.clear();
  pending_pos_ = 0;
  // A controller that re-enumerated may have a new hidraw node: messages name the new one.
  const std::string old_head = "hid:" + reconnect_.device.path;
  if (same->path != reconnect_.device.path && description_.rfind(old_head, 0) == 0) {
    description_ = "hid:" + same->path + description_.substr(old_head.size());
  }
  reconnect_.device = *same;
  return true;
}

Status HidTransport::write(ByteView bytes) {
  auto frame = lsc::decode_serial(bytes);
  if (!frame) {
    return make_error(description_ + " takes one whole frame per write: " + frame.error().message);
  }
  auto report = lsc::encode_hid_report(*frame);
  if (!report) return make_error("cannot send to " + description_ + ": " + report.error().message);
  auto written = device_->write(*report);
  if (!written)
    return make_error("cannot write to " + description_ + ": " + written.error().message);
  if (*written != report->size()) {
    return make_error("short write to " + description_ + ": " + std::to_string(*written) + " of " +
                      std::to_string(report->size()) + " bytes");
  }
  return Ok{};
}

std::size_t HidTransport::hand_out(std::span<std::uint8_t> buffer) {
  std::size_t n = std::min(buffer.size(), pending_.size() - pending_pos_);
  std::memcpy(buffer.data(), pending_.data() + pending_pos_, n);
  pending_pos_ += n;
  if (pending_pos_ == pending_.size()) {
    pending_.clear();
    pending_pos_ = 0;
  }
  return n;
}

io::ReadResult HidTransport::read(std::span<std::uint8_t> buffer, io::TimePoint deadline) {
  if (buffer.empty()) return {io::ReadStatus::Error, 0, "read into an empty buffer"};
  if (!pending_.empty()) return {io::ReadStatus::Data, hand_out(buffer), {}};
  std::array<std::uint8_t, lsc::kHidReportData> report{};
  for (;;) {
    io::TimePoint before = clock_.now();
    HidRead r = device_->read(report, timeout_ms(deadline - before));
    switch (r.state) {
      case HidRead::State::Report: {
        ByteView got(report.data(), std::min(r.count, report.size()));
        auto frame = lsc::decode_hid_report(got);
        if (frame) {
          auto serial = lsc::encode_serial(*frame);
          pending_ = serial ? std::move(*serial) : undecodable_report(got);
        } else {
          pending_ = undecodable_report(got);
        }
        pending_pos_ = 0;
        if (pending_.empty()) continue;  // an all-zero report carries nothing
        return {io::ReadStatus::Data, hand_out(buffer), {}};
      }
      case HidRead::State::Timeout: {
        io::TimePoint after = clock_.now();
        // As in SerialTransport: a clock that stood still while hidapi waited is a test clock.
        if (after >= deadline || after == before) return {io::ReadStatus::Timeout, 0, {}};
        continue;
      }
      case HidRead::State::Gone:
        return {io::ReadStatus::HangUp, 0, description_ + " was unplugged: " + r.error};
      case HidRead::State::Error:
        return {io::ReadStatus::Error, 0, "cannot read from " + description_ + ": " + r.error};
    }
  }
}

void HidTransport::discard_input() {
  pending_.clear();
  pending_pos_ = 0;
  std::array<std::uint8_t, lsc::kHidReportData> report{};
  for (int i = 0; i < kMaxDrainedReports; ++i) {
    if (device_->read(report, 0).state != HidRead::State::Report) break;
  }
}

}  // namespace seqc::transport
