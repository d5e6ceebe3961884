// Opening the Raspblock board's link for `seqc play` and `seqc show`: a serial port at 115200
// baud, or `emu:raspblock`, the board emulator in this process stamped with the caller's clock.
#pragma once

#include <memory>
#include <string>

#include "runtime/cli/context.hpp"
#include "runtime/cli/port_open.hpp"
#include "runtime/emulator/raspblock_emulator.hpp"
#include "runtime/io/transport.hpp"

namespace seqc::cli {

struct OpenedBoard {
  std::unique_ptr<io::Transport> link;
  std::unique_ptr<emu::RaspblockEmulator> emulator;  // emu:raspblock only
};

// `what` names the file in messages ("car-dance.yaml is for the raspblock").
Result<OpenedBoard> open_board_port(const std::string& port, const std::string& what, Context& ctx,
                                    ExitCode& code);

}  // namespace seqc::cli
