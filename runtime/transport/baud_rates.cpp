#include "runtime/transport/baud_rates.hpp"

#include <array>
#include <utility>

namespace seqc::transport {
namespace {

// termios has no arbitrary-rate API without termios2/BOTHER; the named constants cover every
// rate these boards use (9600 for the servo controller, 115200 for the Raspblock board).
// Ascending, so the list in messages reads naturally.
constexpr std::array<std::pair<std::uint32_t, speed_t>, 24> kRates{{
    {300, B300},         {600, B600},         {1200, B1200},       {1800, B1800},
    {2400, B2400},       {4800, B4800},       {9600, B9600},       {19200, B19200},
    {38400, B38400},     {57600, B57600},     {115200, B115200},   {230400, B230400},
    {460800, B460800},   {500000, B500000},   {576000, B576000},   {921600, B921600},
    {1000000, B1000000}, {1152000, B1152000}, {1500000, B1500000}, {2000000, B2000000},
    {2500000, B2500000}, {3000000, B3000000}, {3500000, B3500000}, {4000000, B4000000},
}};

constexpr std::array<std::uint32_t, kRates.size()> rate_values() {
  std::array<std::uint32_t, kRates.size()> out{};
  for (std::size_t i = 0; i < kRates.size(); ++i) out[i] = kRates[i].first;
  return out;
}

constexpr auto kRateValues = rate_values();

}  // namespace

std::span<const std::uint32_t> supported_baud_rates() { return kRateValues; }

std::optional<speed_t> baud_to_speed(std::uint32_t baud) {
  for (const auto& [rate, speed] : kRates) {
    if (rate == baud) return speed;
  }
  return std::nullopt;
}

std::string supported_baud_list() {
  std::string out;
  for (std::uint32_t rate : kRateValues) {
    if (!out.empty()) out += ", ";
    out += std::to_string(rate);
  }
  return out;
}

}  // namespace seqc::transport
