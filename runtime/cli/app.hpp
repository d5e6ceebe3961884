// Builds the seqc command line and runs one subcommand. Each subcommand lives in its own
// cmd_<name>.cpp and adds itself through the add_*_command functions in commands.hpp.
#pragma once

#include "runtime/cli/context.hpp"
#include "runtime/cli/exit_codes.hpp"

namespace seqc::cli {

int run(int argc, const char* const* argv, Context& ctx);

}  // namespace seqc::cli
