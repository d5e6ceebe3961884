// Builds the seqc command line and runs one subcommand. Each subcommand lives in its own
// cmd_<name>.cpp and adds itself through the add_*_command functions in commands.hpp.
//
// Global options (-q/--quiet, -v/--verbose, --color) may stand before or after the subcommand.
// A mistyped subcommand or option is a usage error (exit 2) with "did you mean", and
// `seqc help [SUBCOMMAND...]` prints the same text as `--help`.
#pragma once

#include "runtime/cli/context.hpp"
#include "runtime/cli/exit_codes.hpp"

// CLI11 is large and header-only: only the files that build the command line parse it.
namespace CLI {
class App;
}  // namespace CLI

namespace seqc::cli {

struct Outcome;  // commands.hpp

inline constexpr const char* kAppDescription =
    "seqc: compile, check and upload motion sequences for hobby servo robots";

// The whole command line, every subcommand added; `outcome` receives the exit status. The
// man page and shell completions are generated from this same tree (tools/seqc_docgen.cpp).
void build_app(CLI::App& app, Context& ctx, Outcome& outcome);

int run(int argc, const char* const* argv, Context& ctx);

}  // namespace seqc::cli
