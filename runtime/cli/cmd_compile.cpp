// seqc compile FILE [--group N] [--emit hex|listing|json] [-o OUT] [--strict]
#include <map>
#include <string>

#include "compiler/backend/listing.hpp"
#include "compiler/backend/raspblock_stream.hpp"
#include "compiler/backend/servo_backend.hpp"
#include "runtime/cli/commands.hpp"
#include "runtime/cli/compile_report.hpp"
#include "runtime/cli/group_dialect.hpp"
#include "runtime/cli/session_text.hpp"
#include "runtime/io/disk.hpp"

namespace seqc::cli {

void add_compile_command(CLI::App& app, Context& ctx, Outcome& result) {
  struct Options {
    std::string file;
    int group = 0;
    std::string emit = "hex";
    std::string output;
    bool strict = false;
    bool dry_run = false;
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
  cmd->add_flag("--dry-run", opts->dry_run,
                "Print every frame `seqc upload` would send (probe, stop, download, barriers) as "
                "commented hex; `seqc decode -` reads it back");
  cmd->callback([&ctx, &result, opts] {
    Compiled c = compile_and_report(ctx, opts->file, opts->strict);
    result.code = c.code;
    if (const compiler::RaspblockProgram* car = c.output.raspblock_program()) {
      // The Raspblock has no storage: its program is a timed stream (--group does not apply).
      auto frames = backend::plan_stream(*car);
      if (!frames) {
        ctx.err << "seqc: error: " << frames.error().message << "\n";
        result.code = ExitCode::Internal;
        return;
      }
      const std::string text = opts->emit == "hex" ? backend::render_stream_hex(*frames)
                               : opts->emit == "listing"
                                   ? backend::render_stream_listing(*car, *frames, c.output.sources)
                                   : backend::render_stream_json(*car, *frames);
      if (opts->output.empty() || opts->output == "-") {
        ctx.out << text;
      } else if (auto written = io::write_file_atomically(opts->output, text); !written) {
        ctx.err << "seqc: error: cannot write '" << opts->output << "': " << written.error().message
                << "\n";
        result.code = ExitCode::FileError;
      }
      return;
    }
    const compiler::ServoProgram* program = c.output.servo_program();
    if (program == nullptr) return;
    const auto group = static_cast<std::uint8_t>(opts->group);
    auto plan = backend::plan_download(*program, group);
    if (!plan) {
      ctx.err << "seqc: error: " << opts->file << ": " << plan.error().message << "\n";
      result.code = ExitCode::InvalidInput;
      return;
    }
    std::string text;
    if (opts->dry_run) {
      text = dialect_for(*plan)->session_hex(group, false, 1);
    } else if (opts->emit == "hex") {
      text = backend::render_hex(*plan);
    } else if (opts->emit == "listing") {
      text = backend::render_listing(*program, *plan, group, c.output.sources);
    } else {
      text = backend::render_json(*program, *plan, group, c.output.sources);
    }
    if (opts->output.empty() || opts->output == "-") {
      ctx.out << text;
      return;
    }
    if (auto written = io::write_file_atomically(opts->output, text); !written) {
      ctx.err << "seqc: error: " << written.error().message << "\n";
      result.code = ExitCode::FileError;
    }
  });
}

}  // namespace seqc::cli
