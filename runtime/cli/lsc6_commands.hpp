// The device commands on an LSC-6 board (docs/protocol/lsc-6.md): group run, stop and erase
// and direct moves, in that firmware's own dialect. Which board a command talks to is decided
// once, by is_lsc6_board(): the `lsc-6` profile (--robot lsc-6) or the emu:lsc6 port.
//
// The board answers only Run (maybe), EraseAll and downloads, so a stop or a move cannot be
// confirmed: the commands say so instead of waiting. Every other device command (battery,
// speed, servo read/off/mode, offsets, bus info) asks for something the firmware does not have;
// refuse_on_lsc6() turns it down before anything is sent.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "runtime/cli/context.hpp"
#include "runtime/cli/controller_session.hpp"
#include "runtime/cli/exit_codes.hpp"
#include "runtime/protocol/lsc6_messages.hpp"

namespace seqc::cli {

// `robot` is the command's --robot (or ""), `port` its --port.
bool is_lsc6_board(const std::string& robot, const std::string& port);

ExitCode lsc6_run(Context& ctx, const DeviceOptions& device, std::uint8_t group,
                  std::uint16_t times);
ExitCode lsc6_stop(Context& ctx, const DeviceOptions& device);
// `all` must be set: the board's erase wipes every group.
ExitCode lsc6_erase(Context& ctx, const DeviceOptions& device, bool all);
ExitCode lsc6_move(Context& ctx, const DeviceOptions& device, const lsc6::Move& move,
                   const std::string& summary);
// "seqc: error: the LSC-6 board has no COMMAND command ..." and ExitCode::Usage.
ExitCode refuse_on_lsc6(Context& ctx, const std::string& command);

}  // namespace seqc::cli
