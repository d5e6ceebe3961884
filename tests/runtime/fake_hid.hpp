// A scripted stand-in for hidapi: records every output report and every read's timeout, and
// plays back queued input reports.
#pragma once

#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "runtime/transport/hid_backend.hpp"

namespace seqc::transport::testing {

struct FakeHidState {
  std::vector<Bytes> written;      // output reports, exactly as hid_write got them
  std::deque<HidRead> script;      // what the next reads return (after `reports`)
  std::deque<Bytes> reports;       // queued input reports
  std::vector<int> read_timeouts;  // timeout_ms of every read
  bool endless = false;            // always has another report (a chatty device)
  std::string write_error;         // non-empty: hid_write fails with this text
};

class FakeHidDevice final : public HidDevice {
 public:
  explicit FakeHidDevice(std::shared_ptr<FakeHidState> state) : s_(std::move(state)) {}

  Result<std::size_t> write(ByteView report) override {
    if (!s_->write_error.empty()) return make_error(s_->write_error);
    s_->written.emplace_back(report.begin(), report.end());
    return report.size();
  }

  HidRead read(std::span<std::uint8_t> report, int timeout_ms) override {
    s_->read_timeouts.push_back(timeout_ms);
    if (s_->endless) {
      report[0] = 0x55;
      return {HidRead::State::Report, 1, {}};
    }
    if (!s_->reports.empty()) {
      Bytes next = std::move(s_->reports.front());
      s_->reports.pop_front();
      std::size_t n = std::min(next.size(), report.size());
      std::copy(next.begin(), next.begin() + static_cast<std::ptrdiff_t>(n), report.begin());
      return {HidRead::State::Report, n, {}};
    }
    if (!s_->script.empty()) {
      HidRead r = s_->script.front();
      s_->script.pop_front();
      return r;
    }
    return {HidRead::State::Timeout, 0, {}};
  }

 private:
  std::shared_ptr<FakeHidState> s_;
};

class FakeHidBackend final : public HidBackend {
 public:
  std::vector<HidDeviceInfo> devices;
  std::map<std::string, std::string> open_errors;  // path -> error message
  std::vector<std::string> opened;
  std::shared_ptr<FakeHidState> state = std::make_shared<FakeHidState>();
  // Called before each enumeration (e.g. to plug a device back in at a time on a test clock).
  std::function<void(FakeHidBackend&)> before_enumerate;

  Result<std::vector<HidDeviceInfo>> enumerate(std::uint16_t vendor_id,
                                               std::uint16_t product_id) override {
    if (before_enumerate) before_enumerate(*this);
    std::vector<HidDeviceInfo> out;
    for (const auto& d : devices) {
      if (d.vendor_id == vendor_id && d.product_id == product_id) out.push_back(d);
    }
    return out;
  }

  Result<std::unique_ptr<HidDevice>> open(const std::string& path) override {
    if (auto it = open_errors.find(path); it != open_errors.end()) return make_error(it->second);
    opened.push_back(path);
    return std::unique_ptr<HidDevice>(new FakeHidDevice(state));
  }
};

inline HidDeviceInfo lobot(std::string path, std::string serial = "") {
  return HidDeviceInfo{.path = std::move(path),
                       .vendor_id = kLobotVendorId,
                       .product_id = kLobotProductId,
                       .product = "LOBOT",
                       .manufacturer = "MyUSB_HID",
                       .serial_number = std::move(serial),
                       .interface_number = 0};
}

}  // namespace seqc::transport::testing
