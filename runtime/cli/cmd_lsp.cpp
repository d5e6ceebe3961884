// seqc lsp [--stdio]: the language server (runtime/lsp/server.hpp) on standard input and
// output, for editors (docs/editors.md). Its diagnostics are those of `seqc check`: a
// choreography is checked from home and may take several groups, a song is decoded to check
// the dance against it. The exit status is the protocol's: 0 after shutdown then exit, 1
// otherwise.
#include <unistd.h>

#include <memory>

#include <CLI/CLI.hpp>

#include "runtime/cli/commands.hpp"
#include "runtime/cli/version.hpp"
#include "runtime/lsp/server.hpp"
#include "runtime/lsp/stdio_channel.hpp"

namespace seqc::cli {

void add_lsp_command(CLI::App& app, Context& ctx, Outcome& result) {
  auto stdio = std::make_shared<bool>(false);
  CLI::App* cmd = app.add_subcommand(
      "lsp", "Run the language server for editors (LSP over standard input and output)");
  // Clients pass --stdio to every server that talks over standard input and output.
  cmd->add_flag("--stdio", *stdio, "Talk over standard input and output (the only way; accepted)");
  // The callback holds the flag's storage, so it lives as long as the command line that writes it.
  cmd->callback([&ctx, &result, stdio] {
    (void)stdio;
    lsp::ServerOptions options;
    compiler::RobotStart home;
    home.assume_home = true;
    options.compile.program = {.songs = ctx.songs, .chain = true, .start = home};
    options.compile.performers = {.songs = ctx.songs};
    options.version = kVersion;
    lsp::FdInput in(STDIN_FILENO);
    lsp::FdOutput out(STDOUT_FILENO);
    lsp::Server server(out, ctx.files, options);
    result.code = server.run(in) == 0 ? ExitCode::Ok : ExitCode::InvalidInput;
  });
}

}  // namespace seqc::cli
