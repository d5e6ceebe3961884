// `seqc emulate lsc6`: the LSC-6 firmware emulator (emu::Lsc6Emulator) on a pseudo-terminal,
// for `seqc emulate` (cmd_emulate.cpp). Prints the terminal's path on stdout; on exit --record
// writes every frame the board's receiver completed and --dump-groups its stored groups.
#pragma once

#include <optional>
#include <string>

#include "runtime/cli/context.hpp"
#include "runtime/cli/exit_codes.hpp"

namespace seqc::cli {

struct Lsc6EmulateArgs {
  std::optional<std::uint32_t> baud;  // default 9600
  std::string options;                // as emu:lsc6?OPTIONS: drop, seed, no-run-reply, no-finish
  std::optional<std::uint64_t> seed;
  std::optional<std::string> link;
  std::optional<std::string> record;
  std::optional<std::string> dump_groups;
};

ExitCode run_emulate_lsc6(const Lsc6EmulateArgs& args, Context& ctx);

}  // namespace seqc::cli
