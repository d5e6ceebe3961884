#include "runtime/transport/port_spec.hpp"

#include <array>
#include <charconv>

#include <fmt/format.h>

#include "runtime/transport/baud_rates.hpp"

namespace seqc::transport {
namespace {

constexpr std::string_view kForms =
    "expected a device path (/dev/ttyUSB0[@BAUD]), serial:PATH[@BAUD], pty:PATH[@BAUD], hid, "
    "hid:PATH, emu:xarm, emu:xarm-hid, emu:lsc6 or emu:raspblock";

constexpr std::array<std::string_view, 4> kEmulators{"xarm", "xarm-hid", "lsc6", "raspblock"};

Error port_error(std::string_view text, std::string_view why) {
  return make_error("invalid port '" + std::string(text) + "': " + std::string(why));
}

// PATH[@BAUD] for serial-like forms. The last '@' starts the rate, so paths containing '@'
// can still be given as long as they end with an explicit rate.
Result<PortSpec> parse_serial(std::string_view whole, std::string_view rest) {
  PortSpec spec;
  spec.kind = PortKind::Serial;
  std::string_view path = rest;
  if (auto at = rest.rfind('@'); at != std::string_view::npos) {
    path = rest.substr(0, at);
    std::string_view rate = rest.substr(at + 1);
    std::uint32_t baud = 0;
    auto [end, ec] = std::from_chars(rate.data(), rate.data() + rate.size(), baud);
    if (rate.empty() || ec != std::errc{} || end != rate.data() + rate.size()) {
      return port_error(whole, fmt::format("'{}' is not a baud rate (e.g. @115200)", rate));
    }
    if (!baud_to_speed(baud)) {
      return port_error(whole, "unsupported baud rate " + std::to_string(baud) +
                                   "; supported: " + supported_baud_list());
    }
    spec.baud = baud;
  }
  if (path.empty()) return port_error(whole, "the device path is missing");
  spec.path = std::string(path);
  return spec;
}

Result<PortSpec> parse_emulator(std::string_view whole, std::string_view rest) {
  PortSpec spec;
  spec.kind = PortKind::Emulator;
  std::string_view name = rest;
  if (auto q = rest.find('?'); q != std::string_view::npos) {
    name = rest.substr(0, q);
    spec.emulator_options = std::string(rest.substr(q + 1));
  }
  for (std::string_view known : kEmulators) {
    if (name == known) {
      spec.emulator = std::string(name);
      return spec;
    }
  }
  return port_error(whole, name.empty() ? "the emulator name is missing; use emu:xarm, "
                                          "emu:xarm-hid, emu:lsc6 or emu:raspblock"
                                        : "unknown emulator '" + std::string(name) +
                                              "'; use emu:xarm, emu:xarm-hid, emu:lsc6 or "
                                              "emu:raspblock");
}

}  // namespace

PortSpec serial_port(std::string path, std::optional<std::uint32_t> baud) {
  PortSpec spec;
  spec.kind = PortKind::Serial;
  spec.path = std::move(path);
  spec.baud = baud;
  return spec;
}

PortSpec hid_port(std::string path) {
  PortSpec spec;
  spec.kind = PortKind::Hid;
  spec.path = std::move(path);
  return spec;
}

PortSpec emulator_port(std::string name, std::string options) {
  PortSpec spec;
  spec.kind = PortKind::Emulator;
  spec.emulator = std::move(name);
  spec.emulator_options = std::move(options);
  return spec;
}

Result<PortSpec> parse_port(std::string_view text) {
  if (text.empty()) return make_error("invalid port '': " + std::string(kForms));
  if (text == "hid") return hid_port();
  auto colon = text.find(':');
  auto slash = text.find('/');
  // A scheme is the text before a ':' that comes before any '/'.
  if (colon != std::string_view::npos && (slash == std::string_view::npos || colon < slash)) {
    std::string_view scheme = text.substr(0, colon);
    std::string_view rest = text.substr(colon + 1);
    if (scheme == "serial" || scheme == "pty") return parse_serial(text, rest);
    if (scheme == "emu") return parse_emulator(text, rest);
    if (scheme == "hid") {
      if (rest.empty()) return port_error(text, "the HID path is missing (e.g. hid:/dev/hidraw3)");
      return hid_port(std::string(rest));
    }
    return port_error(text,
                      "unknown port kind '" + std::string(scheme) + ":'; " + std::string(kForms));
  }
  if (slash == std::string_view::npos) {
    // A bare device name such as ttyUSB0 lives in /dev.
    return parse_serial(text, "/dev/" + std::string(text));
  }
  return parse_serial(text, text);
}

std::string format_port(const PortSpec& spec) {
  switch (spec.kind) {
    case PortKind::Serial:
      return spec.path + (spec.baud ? "@" + std::to_string(*spec.baud) : "");
    case PortKind::Hid:
      return spec.path.empty() ? "hid" : "hid:" + spec.path;
    case PortKind::Emulator:
      return "emu:" + spec.emulator +
             (spec.emulator_options.empty() ? "" : "?" + spec.emulator_options);
  }
  return {};
}

}  // namespace seqc::transport
