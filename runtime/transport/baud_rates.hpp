// The baud rates a serial port can be set to: the standard POSIX/Linux termios speeds.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>

#include <termios.h>

namespace seqc::transport {

// The servo controller's UART speed (docs/protocol/servo-controller.md, "Framing").
inline constexpr std::uint32_t kDefaultBaud = 9600;

// Every rate accepted by `--port PATH@BAUD`, ascending.
std::span<const std::uint32_t> supported_baud_rates();

// The termios speed constant for `baud`, or nothing when the rate is not supported.
std::optional<speed_t> baud_to_speed(std::uint32_t baud);

// "1200, 2400, ..., 4000000" for error messages.
std::string supported_baud_list();

}  // namespace seqc::transport
