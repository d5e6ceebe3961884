// The serial link to the Raspblock board as the compiler sees it: how many bytes each packet
// takes on the wire and whether a stream fits the link (docs/raspblock.md, "Link capacity").
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "compiler/program/raspblock_program.hpp"
#include "protocol/raspblock/raspblock.hpp"

namespace seqc::compiler {

// 115200 baud 8N1 (docs/protocol/raspblock.md): 10 bits per byte, so 11,520 bytes per second.
inline constexpr std::uint32_t kRaspblockBytesPerSecond = raspblock::kBaud / 10;

// Decision, not a fact from the documents: the link is judged over every window of this many
// milliseconds that starts at a packet. A whole second would let a burst fall up to a second
// behind its send times; 100 ms keeps any backlog the check lets through below 100 ms while
// still allowing the short bursts a step's first instant makes (PID + gimbal + servos + rocker).
inline constexpr std::uint32_t kCapacityWindowMs = 100;
inline constexpr std::size_t kCapacityWindowBytes =
    std::size_t{kRaspblockBytesPerSecond} * kCapacityWindowMs / 1000;  // 1,152

// Bytes of one packet on the wire: FF FE FUNC LEN DATA CHK.
std::size_t wire_size(const raspblock::Packet& packet);

// A window that needs more than the link carries.
struct Overload {
  std::size_t first = 0;      // index of the packet that starts the window
  std::uint32_t from_ms = 0;  // the window [from_ms, from_ms + kCapacityWindowMs)
  std::size_t bytes = 0;      // bytes sent in it
  std::uint64_t bytes_per_second() const { return std::uint64_t{bytes} * 1000 / kCapacityWindowMs; }
};

// Every overloaded window, but only the first for each packet source (a step in a loop is
// reported once, where it first overflows).
std::vector<Overload> find_overloads(const std::vector<TimedPacket>& packets);

}  // namespace seqc::compiler
