#include "runtime/transport/open_port.hpp"

#include <cstdio>

#include "runtime/transport/hid_transport.hpp"
#include "runtime/transport/hidapi_backend.hpp"
#include "runtime/transport/serial_transport.hpp"

namespace seqc::transport {
namespace {

std::string hid_description(const std::string& path, const std::string& product) {
  char ids[16];
  std::snprintf(ids, sizeof ids, "%04x:%04x", kLobotVendorId, kLobotProductId);
  return "hid:" + path + " (" + ids + (product.empty() ? "" : " " + product) + ")";
}

// `backend` is `hid`, shared so that reopen() can find the device again after an unplug.
Result<std::unique_ptr<io::Transport>> open_hid(const PortSpec& spec, io::Clock& clock,
                                                HidBackend& hid,
                                                std::shared_ptr<HidBackend> backend) {
  std::string path = spec.path;
  std::string product;
  HidDeviceInfo identity;
  if (!path.empty()) {
    // An explicit path: its serial number, if the backend lists it, tells it apart on reopen.
    if (auto all = find_lobot_devices(hid)) {
      for (const auto& d : *all) {
        if (d.path == path) identity = d;
      }
    }
    identity.path = path;
  } else {
    auto found = find_lobot_devices(hid);
    if (!found) return found.error();
    if (found->empty()) {
      return make_error(
          "no xArm controller found over USB HID (0483:5750 \"LOBOT\")\n"
          "  hint: check the cable and that the controller is on; if it is, install the udev "
          "rule (docs/ports.md)");
    }
    if (found->size() > 1) {
      std::string msg = "several xArm controllers found over USB HID; choose one with --port:";
      for (const auto& d : *found) msg += "\n  hid:" + d.path;
      return make_error(msg);
    }
    path = found->front().path;
    product = found->front().product;
    identity = found->front();
  }
  auto device = hid.open(path);
  if (!device) return device.error();
  return std::unique_ptr<io::Transport>(new HidTransport(
      std::move(*device), clock, hid_description(path, product.empty() ? "LOBOT" : product),
      HidReconnect{std::move(backend), std::move(identity)}));
}

Result<std::unique_ptr<io::Transport>> open_serial(const PortSpec& spec, io::Clock& clock,
                                                   std::uint32_t default_baud) {
  SerialOptions options;
  options.baud = spec.baud.value_or(default_baud);
  auto serial = SerialTransport::open(spec.path, clock, options);
  if (!serial) return serial.error();
  return std::unique_ptr<io::Transport>(std::move(*serial));
}

Error emulator_spec_error(const PortSpec& spec) {
  return make_error("internal error: " + format_port(spec) +
                    " is an emulator port; the emulator builds its own transport");
}

}  // namespace

Result<std::unique_ptr<io::Transport>> open_port(const PortSpec& spec, io::Clock& clock,
                                                 std::uint32_t default_baud, HidBackend& hid) {
  switch (spec.kind) {
    case PortKind::Serial:
      return open_serial(spec, clock, default_baud);
    case PortKind::Hid:
      // The caller keeps `hid` alive as long as the transport (open_port.hpp): not owned here.
      return open_hid(spec, clock, hid, std::shared_ptr<HidBackend>(std::shared_ptr<void>(), &hid));
    case PortKind::Emulator:
      break;
  }
  return emulator_spec_error(spec);
}

Result<std::unique_ptr<io::Transport>> open_port(const PortSpec& spec, io::Clock& clock,
                                                 std::uint32_t default_baud) {
  // Only HID ports start hidapi.
  if (spec.kind == PortKind::Hid) {
    auto hid = std::make_shared<HidapiBackend>();
    return open_hid(spec, clock, *hid, hid);
  }
  if (spec.kind == PortKind::Serial) return open_serial(spec, clock, default_baud);
  return emulator_spec_error(spec);
}

}  // namespace seqc::transport
