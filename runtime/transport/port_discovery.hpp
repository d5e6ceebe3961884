// Finding the controller when no --port is given, and `seqc ports`.
//
// Candidates: every USB serial port (/dev/serial/by-id/* resolved to its device, then any
// /dev/ttyUSB* or /dev/ttyACM* without a by-id link), the on-board UARTs (/dev/ttyAMA*, where a
// Raspblock board sits on a Raspberry Pi, and /dev/ttyS*) whose hardware answers (the kernel's
// serial core reports a UART type other than 0, "unknown", in /sys/class/tty/NAME/type), and
// every xArm HID device (0483:5750 with product string "LOBOT"). The file system and hidapi
// come in through DeviceLister.
//
// On-board UARTs are listed but never chosen when --port is left out: most PCs have a ttyS0
// with nothing on it, and a Raspberry Pi's console may be on ttyAMA0.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "base/result.hpp"
#include "runtime/transport/hid_backend.hpp"
#include "runtime/transport/port_spec.hpp"

namespace seqc::transport {

// What discovery needs from the system.
class DeviceLister {
 public:
  virtual ~DeviceLister() = default;
  // Names of the entries in `dir` (no "." or ".."); empty when it does not exist.
  virtual std::vector<std::string> list_directory(const std::string& dir) const = 0;
  // The absolute path `path` resolves to (symlinks followed), or nothing when it is dangling.
  virtual std::optional<std::string> resolve(const std::string& path) const = 0;
  // The xArm HID devices (find_lobot_devices on the real backend).
  virtual Result<std::vector<HidDeviceInfo>> lobot_hid_devices() const = 0;
  // The first line of a small text file (sysfs attributes), or nothing if it cannot be read.
  virtual std::optional<std::string> read_line(const std::string& path) const {
    (void)path;
    return std::nullopt;
  }
};

struct PortCandidate {
  PortKind kind = PortKind::Serial;
  // Serial: the stable /dev/serial/by-id path when there is one, else the device.
  // Hid: the hidapi path.
  std::string path;
  std::string device;         // Serial: the device node (/dev/ttyUSB0). Hid: same as path.
  HidDeviceInfo hid;          // Hid only: product, manufacturer, serial number
  bool onboard_uart = false;  // ttyAMA*/ttyS*: listed, never chosen by default
  friend bool operator==(const PortCandidate&, const PortCandidate&) = default;

  PortSpec spec() const;
};

PortCandidate serial_candidate(std::string path, std::string device);
PortCandidate hid_candidate(const HidDeviceInfo& info);

struct Discovery {
  std::vector<PortCandidate> candidates;  // serial first, each group sorted by path
  std::vector<std::string> warnings;      // e.g. hidapi could not enumerate
};

Discovery discover_ports(const DeviceLister& lister);

// Exactly one candidate (on-board UARTs aside): it. None: "no controller found" with hints.
// Several: the list and "use --port".
Result<PortCandidate> select_default_port(const std::vector<PortCandidate>& candidates);

// The `seqc ports` listing, one line per candidate:
//   /dev/serial/by-id/usb-1a86_USB_Serial-if00-port0 -> /dev/ttyUSB0
//   hid:/dev/hidraw3  LOBOT (MyUSB_HID) serial 0001
//   /dev/ttyAMA0  on-board UART
std::string format_port_list(const std::vector<PortCandidate>& candidates);
// `seqc ports --json`: [{"port": "...", "kind": "serial|uart|hid", "device": "...",
// "product": "...", "manufacturer": "...", "serial_number": "..."}] (the last three for HID).
std::string format_port_json(const std::vector<PortCandidate>& candidates);

// The message for "nothing found" (shared by select_default_port and `seqc ports`).
std::string no_controller_message();

// DeviceLister over the real /dev and hidapi.
class SystemDeviceLister final : public DeviceLister {
 public:
  explicit SystemDeviceLister(HidBackend& hid) : hid_(hid) {}
  std::vector<std::string> list_directory(const std::string& dir) const override;
  std::optional<std::string> resolve(const std::string& path) const override;
  Result<std::vector<HidDeviceInfo>> lobot_hid_devices() const override;
  std::optional<std::string> read_line(const std::string& path) const override;

 private:
  HidBackend& hid_;
};

}  // namespace seqc::transport
