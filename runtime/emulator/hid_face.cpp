#include "runtime/emulator/hid_face.hpp"

#include <algorithm>
#include <cstring>

#include "protocol/lsc/lsc_frame.hpp"
#include "runtime/transport/hid_transport.hpp"

namespace seqc::emu {

EmulatedHidDevice::EmulatedHidDevice(XArmEmulator& emulator, io::ManualClock& clock)
    : emu_(emulator), clock_(clock) {}

Result<std::size_t> EmulatedHidDevice::write(ByteView report) {
  if (report.size() != 1 + lsc::kHidReportData || report[0] != 0) {
    return make_error(
        "the controller's output report is report id 0 and 64 bytes (65 for "
        "hid_write), got " +
        std::to_string(report.size()) + " bytes starting " +
        (report.empty() ? std::string("nowhere") : to_hex(report.first(1))));
  }
  written_.emplace_back(report.begin(), report.end());
  // The frame is what LEN says; the padding never reaches the controller's parser. The parser
  // reads at least the header and LEN before it can judge LEN: a LEN below 2 still hands it
  // those three bytes, so it abandons the frame instead of waiting inside it for a LEN that
  // the next report would supply.
  const ByteView data = report.subspan(1);
  const std::size_t len = data.size() >= 3 && data[0] == 0x55 && data[1] == 0x55
                              ? std::max<std::size_t>(std::size_t{data[2]} + 2, 3)
                              : 0;
  const std::size_t n = std::min(len, data.size());
  const io::TimePoint at =
      std::max(clock_.now(), next_slot_) + transport::HidTransport::kReportInterval;
  next_slot_ = at;
  clock_.sleep_until(at);
  if (n > 0) emu_.receive(data.first(n), at);
  return report.size();
}

void EmulatedHidDevice::collect() {
  const Bytes due = emu_.take_output(clock_.now());
  out_frames_.feed(due);
  while (auto frame = out_frames_.next()) {
    auto serial = lsc::encode_serial(*frame);
    if (!serial) continue;
    Bytes report(lsc::kHidReportData, 0);
    std::copy_n(serial->begin(), std::min(serial->size(), report.size()), report.begin());
    inbox_.push_back(std::move(report));
  }
}

transport::HidRead EmulatedHidDevice::read(std::span<std::uint8_t> report, int timeout_ms) {
  const io::TimePoint deadline = clock_.now() + std::chrono::milliseconds(timeout_ms);
  for (;;) {
    collect();
    if (!inbox_.empty()) {
      const Bytes& r = inbox_.front();
      const std::size_t n = std::min(r.size(), report.size());
      std::copy_n(r.begin(), n, report.begin());
      read_.push_back(r);
      inbox_.pop_front();
      return {transport::HidRead::State::Report, n, {}};
    }
    const auto next = emu_.next_output_at();
    if (!next || *next > deadline) {
      clock_.sleep_until(std::max(clock_.now(), deadline));
      collect();
      if (!inbox_.empty()) continue;
      return {transport::HidRead::State::Timeout, 0, {}};
    }
    clock_.sleep_until(std::max(*next, clock_.now() + io::Duration{1}));
  }
}

Result<std::vector<transport::HidDeviceInfo>> EmulatedHidBackend::enumerate(
    std::uint16_t vendor_id, std::uint16_t product_id) {
  std::vector<transport::HidDeviceInfo> out;
  if ((vendor_id == 0 || vendor_id == transport::kLobotVendorId) &&
      (product_id == 0 || product_id == transport::kLobotProductId)) {
    out.push_back({kEmulatedHidPath, transport::kLobotVendorId, transport::kLobotProductId,
                   std::string(transport::kLobotProduct), "seqc emulator", "", 0});
  }
  return out;
}

Result<std::unique_ptr<transport::HidDevice>> EmulatedHidBackend::open(const std::string& path) {
  if (path != kEmulatedHidPath) return make_error("no emulated HID device at " + path);
  auto device = std::make_unique<EmulatedHidDevice>(emu_, clock_);
  last_ = device.get();
  return std::unique_ptr<transport::HidDevice>(std::move(device));
}

}  // namespace seqc::emu
