// The `--port` argument: what device to talk to and how. Parsing only; opening is open_port.hpp
// (serial and HID) or the emulator's EmulatorTransport (emu:).
//
// Accepted forms (docs/ports.md):
//   /dev/ttyUSB0            a serial port or any terminal device (a pty printed by `seqc emulate`)
//   /dev/ttyUSB0@115200     the same with a baud rate
//   ttyUSB0                 short for /dev/ttyUSB0 (a bare name without '/' or ':')
//   serial:/dev/x[@BAUD]    explicitly serial
//   pty:/dev/pts/3[@BAUD]   explicitly a pseudo-terminal (opened like a serial port)
//   hid                     the one connected xArm controller over USB HID
//   hid:/dev/hidraw3        that HID device (a hidapi path)
//   emu:xarm[?OPTIONS]      the in-process servo controller emulator; OPTIONS go to it verbatim
//   emu:raspblock[?OPTIONS] the in-process Raspblock board emulator
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "base/result.hpp"

namespace seqc::transport {

enum class PortKind {
  Serial,    // termios device: USB serial adapter, UART, pseudo-terminal
  Hid,       // USB HID through hidapi
  Emulator,  // in-process emulator, built by the caller
};

struct PortSpec {
  PortKind kind = PortKind::Serial;
  // Serial: the device path. Hid: the hidapi path, empty for "the one LOBOT device".
  std::string path;
  // Serial only: the rate given with @BAUD (already checked against supported_baud_rates()).
  std::optional<std::uint32_t> baud;
  // Emulator only: "xarm" or "raspblock", and the text after '?' (empty when none).
  std::string emulator;
  std::string emulator_options;

  friend bool operator==(const PortSpec&, const PortSpec&) = default;
};

// Complete specs of each kind (aggregate initialisation of a few fields warns under -Wextra).
PortSpec serial_port(std::string path, std::optional<std::uint32_t> baud = std::nullopt);
PortSpec hid_port(std::string path = {});
PortSpec emulator_port(std::string name, std::string options = {});

// Parses one `--port` value. Errors name the offending text and the accepted forms.
Result<PortSpec> parse_port(std::string_view text);

// The canonical text of a spec; parse_port(format_port(s)) == s.
std::string format_port(const PortSpec& spec);

}  // namespace seqc::transport
