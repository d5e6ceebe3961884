#include "runtime/emulator/group_dump.hpp"

#include <cstddef>
#include <cstdint>

namespace seqc::emu {

std::string dump_groups(const XArmEmulator& emu) {
  std::string out =
      "# seqc emulate xarm: stored groups\n"
      "# group index time_ms id=position ...\n";
  for (std::size_t g = 0; g < kGroupCount; ++g) {
    const auto actions = emu.stored_group(static_cast<std::uint8_t>(g));
    if (!actions) continue;
    for (std::size_t i = 0; i < actions->size(); ++i) {
      const lsc::GroupAction& a = (*actions)[i];
      out += std::to_string(g) + " " + std::to_string(i) + " " + std::to_string(a.time_ms);
      for (const lsc::ServoTarget& s : a.servos) {
        out += " " + std::to_string(s.id) + "=" + std::to_string(s.position);
      }
      out += "\n";
    }
  }
  return out;
}

std::string dump_groups(const Lsc6Emulator& emu) {
  std::string out =
      "# seqc emulate lsc6: stored groups\n"
      "# group index time_ms id=position ...\n";
  for (std::size_t g = 0; g < lsc6::kGroups; ++g) {
    const auto actions = emu.stored_group(static_cast<std::uint8_t>(g));
    if (!actions) continue;
    for (std::size_t i = 0; i < actions->size(); ++i) {
      const lsc6::PlannedAction& a = (*actions)[i];
      out += std::to_string(g) + " " + std::to_string(i) + " " + std::to_string(a.time_ms);
      for (const lsc6::Target& s : a.servos) {
        out += " " + std::to_string(s.id) + "=" + std::to_string(s.position);
      }
      out += "\n";
    }
  }
  return out;
}

}  // namespace seqc::emu
