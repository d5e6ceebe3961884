#include "runtime/transport/port_discovery.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <system_error>

namespace seqc::transport {
namespace {

constexpr const char* kById = "/dev/serial/by-id";

bool is_usb_serial_name(const std::string& name) {
  return name.starts_with("ttyUSB") || name.starts_with("ttyACM");
}

bool is_onboard_uart_name(const std::string& name) {
  return name.starts_with("ttyAMA") || name.starts_with("ttyS");
}

// JSON string without the compiler's helper (transport stays below it): device paths and USB
// strings are short ASCII in practice; anything else is escaped byte by byte.
std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (unsigned char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += static_cast<char>(c);
    } else if (c < 0x20 || c >= 0x7F) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", c);
      out += buf;
    } else {
      out += static_cast<char>(c);
    }
  }
  return out + "\"";
}

std::string describe_hid(const HidDeviceInfo& info) {
  std::string out = info.product.empty() ? "USB HID" : info.product;
  if (!info.manufacturer.empty()) out += " (" + info.manufacturer + ")";
  if (!info.serial_number.empty()) out += " serial " + info.serial_number;
  return out;
}

std::string candidate_line(const PortCandidate& c) {
  if (c.kind == PortKind::Hid) return format_port(c.spec()) + "  " + describe_hid(c.hid);
  if (c.onboard_uart) return c.path + "  on-board UART";
  if (c.path != c.device) return c.path + " -> " + c.device;
  return c.path;
}

}  // namespace

PortSpec PortCandidate::spec() const {
  return kind == PortKind::Hid ? hid_port(path) : serial_port(path);
}

PortCandidate serial_candidate(std::string path, std::string device) {
  PortCandidate c;
  c.kind = PortKind::Serial;
  c.path = std::move(path);
  c.device = std::move(device);
  return c;
}

PortCandidate hid_candidate(const HidDeviceInfo& info) {
  PortCandidate c;
  c.kind = PortKind::Hid;
  c.path = info.path;
  c.device = info.path;
  c.hid = info;
  return c;
}

Discovery discover_ports(const DeviceLister& lister) {
  Discovery out;
  std::set<std::string> covered;  // device nodes already listed through a by-id link
  std::vector<PortCandidate> serial;
  for (const std::string& name : lister.list_directory(kById)) {
    std::string link = std::string(kById) + "/" + name;
    auto device = lister.resolve(link);
    if (!device) continue;  // dangling: the adapter was just unplugged
    serial.push_back(serial_candidate(link, *device));
    covered.insert(*device);
  }
  for (const std::string& name : lister.list_directory("/dev")) {
    if (!is_usb_serial_name(name)) continue;
    std::string device = "/dev/" + name;
    if (covered.count(device) != 0) continue;
    serial.push_back(serial_candidate(device, device));
  }
  std::sort(serial.begin(), serial.end(),
            [](const auto& a, const auto& b) { return a.path < b.path; });
  out.candidates = std::move(serial);

  std::vector<PortCandidate> uarts;
  for (const std::string& name : lister.list_directory("/dev")) {
    if (!is_onboard_uart_name(name)) continue;
    const auto type = lister.read_line("/sys/class/tty/" + name + "/type");
    if (!type || type->empty() || *type == "0") continue;  // no UART behind the node
    PortCandidate c = serial_candidate("/dev/" + name, "/dev/" + name);
    c.onboard_uart = true;
    uarts.push_back(std::move(c));
  }
  std::sort(uarts.begin(), uarts.end(),
            [](const auto& a, const auto& b) { return a.path < b.path; });
  out.candidates.insert(out.candidates.end(), uarts.begin(), uarts.end());

  auto hid = lister.lobot_hid_devices();
  if (!hid) {
    out.warnings.push_back("cannot list USB HID devices: " + hid.error().message);
  } else {
    for (const HidDeviceInfo& info : *hid) {
      out.candidates.push_back(hid_candidate(info));
    }
  }
  return out;
}

std::string no_controller_message() {
  return "no controller found (looked for /dev/serial/by-id/*, /dev/ttyUSB*, /dev/ttyACM* and "
         "USB HID 0483:5750 \"LOBOT\")\n"
         "  hint: plug the controller in and turn it on; `dmesg` shows the device it creates\n"
         "  hint: if a HID controller is plugged in but not listed, install the udev rule "
         "(docs/ports.md)\n"
         "  hint: a Raspblock board on a Raspberry Pi is on the UART: --port /dev/ttyAMA0@115200\n"
         "  hint: to try without hardware: --port emu:xarm";
}

Result<PortCandidate> select_default_port(const std::vector<PortCandidate>& all) {
  std::vector<PortCandidate> candidates;
  for (const PortCandidate& c : all) {
    if (!c.onboard_uart) candidates.push_back(c);
  }
  if (candidates.size() == 1) return candidates.front();
  if (candidates.empty()) return make_error(no_controller_message());
  std::string msg =
      std::to_string(candidates.size()) + " possible controllers found; choose one with --port:";
  for (const auto& c : candidates) msg += "\n  " + candidate_line(c);
  return make_error(msg);
}

std::string format_port_list(const std::vector<PortCandidate>& candidates) {
  std::string out;
  for (const auto& c : candidates) out += candidate_line(c) + "\n";
  return out;
}

std::string format_port_json(const std::vector<PortCandidate>& candidates) {
  std::string out = "[";
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    const PortCandidate& c = candidates[i];
    const char* kind = c.kind == PortKind::Hid ? "hid" : (c.onboard_uart ? "uart" : "serial");
    out += (i ? ",\n  {" : "\n  {") + std::string("\"port\": ") + quoted(format_port(c.spec())) +
           ", \"kind\": \"" + kind + "\", \"device\": " + quoted(c.device);
    if (c.kind == PortKind::Hid) {
      out += ", \"product\": " + quoted(c.hid.product) +
             ", \"manufacturer\": " + quoted(c.hid.manufacturer) +
             ", \"serial_number\": " + quoted(c.hid.serial_number);
    }
    out += "}";
  }
  return out + (candidates.empty() ? "]\n" : "\n]\n");
}

std::optional<std::string> SystemDeviceLister::read_line(const std::string& path) const {
  std::ifstream in(path);
  std::string line;
  if (!in || !std::getline(in, line)) return std::nullopt;
  return line;
}

std::vector<std::string> SystemDeviceLister::list_directory(const std::string& dir) const {
  std::vector<std::string> names;
  std::error_code ec;
  for (std::filesystem::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    names.push_back(it->path().filename().string());
  }
  return names;
}

std::optional<std::string> SystemDeviceLister::resolve(const std::string& path) const {
  std::error_code ec;
  auto target = std::filesystem::canonical(path, ec);
  if (ec) return std::nullopt;
  return target.string();
}

Result<std::vector<HidDeviceInfo>> SystemDeviceLister::lobot_hid_devices() const {
  return find_lobot_devices(hid_);
}

}  // namespace seqc::transport
