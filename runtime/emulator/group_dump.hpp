// The text form of the emulated controller's stored action groups, written by
// `seqc emulate xarm --dump-groups FILE` so that a test (or a person) can compare what the
// controller holds with what was compiled:
//
//   # seqc emulate xarm: stored groups
//   # group index time_ms id=position ...
//   0 0 1000 1=500 2=500 3=500 4=500 5=500 6=500
//   0 1 800 1=300 3=300
//
// One line per action: the group (decimal), the action's index in the group from 0, its time
// in milliseconds, then each servo as id=position in the order the controller stored them.
// Groups ascending; only valid groups (a completed download) appear, so a file with just the
// two comment lines means the controller holds no group.
#pragma once

#include <string>

#include "runtime/emulator/lsc6_emulator.hpp"
#include "runtime/emulator/xarm_emulator.hpp"

namespace seqc::emu {

std::string dump_groups(const XArmEmulator& emu);
// The same for an LSC-6 board ("# seqc emulate lsc6: stored groups"): every group whose action
// count is not 0, each action as the player would read it from flash.
std::string dump_groups(const Lsc6Emulator& emu);

}  // namespace seqc::emu
