// seqc compile FILE [--group N] [--emit hex|listing|json] [-o OUT] [--strict] [--dry-run]
// [--port P]
// The board the file is for renders it (runtime/boards); --dry-run lists what `seqc upload`
// would send, from the board's own uploader run against a recording transport.
#include <string>

#include <CLI/CLI.hpp>

#include "runtime/boards/board.hpp"
#include "runtime/boards/dry_run.hpp"
#include "runtime/cli/clock_option.hpp"
#include "runtime/cli/commands.hpp"
#include "runtime/cli/compile_report.hpp"

namespace seqc::cli {
namespace {

boards::Emit emit_of(const std::string& name) {
  if (name == "listing") return boards::Emit::Listing;
  if (name == "json") return boards::Emit::Json;
  return boards::Emit::Hex;
}

}  // namespace

void add_compile_command(CLI::App& app, Context& ctx, Outcome& result) {
  struct Options {
    std::string file;
    int group = 0;
    std::string emit = "hex";
    std::string output;
    bool strict = false;
    ClockScaleOptions clock;
    bool dry_run = false;
    std::string port;
  };
  auto opts = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand(
      "compile", "Compile a choreography into the frames that download it to the controller");
  cmd->add_option("FILE", opts->file, "Choreography file (.yaml)")->required();
  cmd->add_option("--group", opts->group, "Action group to download into")
      ->check(CLI::Range(0, 254))
      ->default_val(0);
  cmd->add_option("--emit", opts->emit,
                  "hex: one frame per line; listing: every field labelled; json: keyframes and "
                  "frames")
      ->check(CLI::IsMember({"hex", "listing", "json"}))
      ->default_val("hex");
  cmd->add_option("-o,--output", opts->output,
                  "Write here instead of stdout (only on success; - is stdout)");
  cmd->add_flag("--strict", opts->strict, "Treat warnings as errors");
  add_clock_options(*cmd, opts->clock);
  cmd->add_flag("--dry-run", opts->dry_run,
                "Print every frame `seqc upload` would send (probe, stop, download, barriers) as "
                "commented hex; `seqc decode -` reads it back");
  add_link_port_option(*cmd, opts->port);
  cmd->callback([&ctx, &result, opts] {
    Compiled c = compile_and_report(ctx, opts->file, opts->strict, SongCheck::Decode, &opts->clock,
                                    boards::port_over_hid(opts->port));
    result.code = c.code;
    if (!c.output.program) return;
    boards::CompiledText text = boards::compiled_text(
        c.output, static_cast<std::uint8_t>(opts->group), opts->dry_run, emit_of(opts->emit));
    if (text.internal) {
      result.code = fail(ctx, ExitCode::Internal, "internal: " + text.error);
    } else if (!text.error.empty()) {
      result.code = fail(ctx, ExitCode::InvalidInput, opts->file + ": " + text.error);
    } else if (const ExitCode w = write_output(ctx, opts->output, text.text, c.output.inputs());
               w != ExitCode::Ok) {
      result.code = w;
    }
  });
}

}  // namespace seqc::cli
