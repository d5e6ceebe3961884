#include "compiler/targets/raspblock/raspblock_link.hpp"

#include <set>
#include <tuple>
#include <type_traits>
#include <variant>

namespace seqc::compiler {
namespace {

// FF FE FUNC LEN + CHK around the data; LEN per layout as in docs/protocol/raspblock.md.
constexpr std::size_t kOverhead = 5;

}  // namespace

std::size_t wire_size(const raspblock::Packet& packet) {
  return kOverhead + std::visit(
                         [](const auto& p) -> std::size_t {
                           using T = std::decay_t<decltype(p)>;
                           if constexpr (std::is_same_v<T, raspblock::PidAdjust>) return 9;
                           if constexpr (std::is_same_v<T, raspblock::GimbalServos>) return 4;
                           if constexpr (std::is_same_v<T, raspblock::SingleServo>) return 3;
                           if constexpr (std::is_same_v<T, raspblock::Rocker>) return 8;
                         },
                         packet);
}

std::vector<Overload> find_overloads(const std::vector<TimedPacket>& packets) {
  std::vector<Overload> out;
  std::set<std::tuple<std::uint32_t, std::uint32_t, std::uint32_t>> reported;
  // Two pointers over the sorted send times: [i, j) are the packets in the window from i.
  std::size_t j = 0;
  std::size_t bytes = 0;
  for (std::size_t i = 0; i < packets.size(); ++i) {
    if (j < i) {
      j = i;
      bytes = 0;
    }
    const std::uint64_t end = std::uint64_t{packets[i].at_ms} + kCapacityWindowMs;
    while (j < packets.size() && packets[j].at_ms < end) bytes += wire_size(packets[j++].packet);
    if (bytes > kCapacityWindowBytes) {
      const Location& at = packets[i].source;
      if (reported.emplace(at.file, at.line, at.column).second) {
        out.push_back(Overload{i, packets[i].at_ms, bytes});
      }
    }
    bytes -= wire_size(packets[i].packet);
  }
  return out;
}

}  // namespace seqc::compiler
