// The few hidapi operations seqc uses, behind an interface so tests can stand in a fake device
// (report layout, padding, draining) without hardware. hidapi_backend.hpp is the real one.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "base/bytes.hpp"
#include "base/result.hpp"

namespace seqc::transport {

// USB identity of the xArm servo controller (docs/protocol/servo-controller.md, "Framing").
// 0483:5750 is STMicroelectronics' generic custom-HID id, shared with unrelated gadgets, so the
// product string must match too.
inline constexpr std::uint16_t kLobotVendorId = 0x0483;
inline constexpr std::uint16_t kLobotProductId = 0x5750;
inline constexpr std::string_view kLobotProduct = "LOBOT";

// One entry of hid_enumerate, strings converted to UTF-8.
struct HidDeviceInfo {
  std::string path;  // hidapi path: /dev/hidrawN with the hidraw backend
  std::uint16_t vendor_id = 0;
  std::uint16_t product_id = 0;
  std::string product;
  std::string manufacturer;
  std::string serial_number;
  int interface_number = -1;
  friend bool operator==(const HidDeviceInfo&, const HidDeviceInfo&) = default;
};

// What one hid_read_timeout call gave.
struct HidRead {
  enum class State {
    Report,   // `count` bytes of one input report
    Timeout,  // nothing within the timeout
    Gone,     // the device was unplugged
    Error,    // anything else; see `error`
  };
  State state = State::Timeout;
  std::size_t count = 0;
  std::string error;
};

class HidDevice {
 public:
  virtual ~HidDevice() = default;
  // hid_write of one whole output report (report id first). Returns the bytes written.
  virtual Result<std::size_t> write(ByteView report) = 0;
  // hid_read_timeout: one input report into `report`; timeout_ms 0 polls without waiting.
  virtual HidRead read(std::span<std::uint8_t> report, int timeout_ms) = 0;
};

class HidBackend {
 public:
  virtual ~HidBackend() = default;
  // hid_enumerate(vendor_id, product_id); the error carries hid_error()'s text.
  virtual Result<std::vector<HidDeviceInfo>> enumerate(std::uint16_t vendor_id,
                                                       std::uint16_t product_id) = 0;
  // hid_open_path. Errors are complete messages (permission hints included).
  virtual Result<std::unique_ptr<HidDevice>> open(const std::string& path) = 0;
};

// The xArm controllers among the devices `backend` sees: VID/PID and product string "LOBOT".
Result<std::vector<HidDeviceInfo>> find_lobot_devices(HidBackend& backend);

}  // namespace seqc::transport
