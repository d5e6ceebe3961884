// One function per subcommand: it adds the subcommand to `app` and sets `result` when it runs.
#pragma once

#include <CLI/CLI.hpp>

#include "runtime/cli/context.hpp"
#include "runtime/cli/exit_codes.hpp"

namespace seqc::cli {

// Where a subcommand's callback stores its exit status.
struct Outcome {
  ExitCode code = ExitCode::Ok;
};

void add_check_command(CLI::App& app, Context& ctx, Outcome& result);
void add_compile_command(CLI::App& app, Context& ctx, Outcome& result);
void add_decode_command(CLI::App& app, Context& ctx, Outcome& result);
void add_simulate_command(CLI::App& app, Context& ctx, Outcome& result);
void add_emulate_command(CLI::App& app, Context& ctx, Outcome& result);

}  // namespace seqc::cli
