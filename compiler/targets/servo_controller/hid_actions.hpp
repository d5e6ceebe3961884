// The USB HID limit on a stored group's actions. Over USB HID each GroupDownload frame travels in
// one 64-byte report, header included (protocol/lsc/lsc_frame.hpp), so an action may name at most
// lsc::kHidMaxActionServos (17) servos; a serial link takes any frame. check_hid_actions()
// reports, at the step an action came from, every step with an action naming more: the error
// upload would otherwise meet only after opening the port.
#pragma once

#include "compiler/frontend/reporter.hpp"
#include "compiler/program/program.hpp"

namespace seqc::compiler {

// One error per step whose actions are too wide, naming its first such action (1-based, as the
// upload counts them) and how many more of its actions are: "action 3 carries 18 servos, a
// 65-byte frame; over USB HID a frame holds at most 64 bytes, its 4-byte header included (at
// most 17 servos per action)".
void check_hid_actions(const ServoProgram& program, Reporter& reporter);

}  // namespace seqc::compiler
