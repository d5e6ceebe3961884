// The two questions that tell the servo-controller family's dialects apart on one line, asked
// by every command that talks to such a board (upload, play, show) when the board it expected
// stayed silent. Neither changes what a board plays.
//
// The LSC-6 question, asked where an xArm-dialect board was expected: a DownloadAction of group
// `group` with total 1 and index 255 (docs/protocol/lsc-6.md). An LSC-6 answers it with
// 55 55 02 19; it writes slot 255, which no group plays (a group holds indices 0-254), neither
// erases the group (index 0 does) nor writes its action count (the last index does). The xArm
// dialect has no command 25, so a working xArm ignores it.
// The xArm question, asked where an LSC-6 was expected: GetBatteryVoltage. The LSC-6 has no such
// command and ignores it; a board of the xArm dialect answers 55 55 04 0f lo hi.
//
// Each is sent once and awaited for its wire time (both frames) plus `margin` on the link's
// clock. Over a link that carries reports (USB HID), only the xArm family is reached, so the
// LSC-6 question is never sent there.
#pragma once

#include <atomic>
#include <cstdint>

#include "runtime/io/clock.hpp"
#include "runtime/io/transport.hpp"

namespace seqc::upload {

// True when an LSC-6 answered the LSC-6 question.
bool lsc6_answers(io::Transport& transport, io::Clock& clock, const std::atomic<bool>* interrupted,
                  std::uint8_t group, io::Duration margin);

// True when a board of the xArm dialect answered GetBatteryVoltage with its voltage.
bool xarm_answers(io::Transport& transport, io::Clock& clock, const std::atomic<bool>* interrupted,
                  io::Duration margin);

}  // namespace seqc::upload
