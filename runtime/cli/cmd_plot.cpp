// seqc plot FILE [-o out.svg] [--group N] [--from T] [--to T]: the program as an SVG picture
// (compiler/backend/plot_svg.hpp). Without -o the SVG goes to stdout.
#include <cmath>
#include <filesystem>
#include <string>

#include "compiler/backend/plot_svg.hpp"
#include "compiler/source/units.hpp"
#include "runtime/cli/commands.hpp"
#include "runtime/cli/compile_report.hpp"
#include "runtime/io/disk.hpp"

namespace seqc::cli {
namespace {

// "1.5s" or "500ms" (beats need the file's tempo: not here).
std::optional<double> window_ms(Context& ctx, const std::string& option, const std::string& text) {
  auto t = compiler::parse_time(text);
  if (!t ||
      (t->unit != compiler::TimeUnit::Milliseconds && t->unit != compiler::TimeUnit::Seconds)) {
    ctx.err << "seqc: error: " << option << " " << text << ": give a time in ms or s, e.g. 1.5s\n";
    return std::nullopt;
  }
  return t->unit == compiler::TimeUnit::Seconds ? t->amount * 1000.0 : t->amount;
}

}  // namespace

void add_plot_command(CLI::App& app, Context& ctx, Outcome& result) {
  struct Options {
    std::string file;
    std::string output = "-";
    int group = 0;
    std::string from, to;
    bool strict = false;
  };
  auto o = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand(
      "plot",
      "Draw a choreography as an SVG: each servo's curve and motion, beats, cues, warnings");
  cmd->add_option("FILE", o->file, "Choreography file (.yaml); - for stdin")->required();
  cmd->add_option("-o,--output", o->output, "Write the SVG here (default: stdout)");
  cmd->add_option("--group", o->group, "The action group it is for (0-254), shown in the title")
      ->check(CLI::Range(0, 254));
  cmd->add_option("--from", o->from, "Start of the time window, e.g. 2s (default: 0)");
  cmd->add_option("--to", o->to, "End of the time window, e.g. 10s (default: the end)");
  cmd->add_flag("--strict", o->strict, "Treat warnings as errors");
  cmd->callback([&ctx, &result, o] {
    backend::PlotOptions options;
    if (!o->from.empty() && !(options.from_ms = window_ms(ctx, "--from", o->from))) {
      result.code = ExitCode::Usage;
      return;
    }
    if (!o->to.empty() && !(options.to_ms = window_ms(ctx, "--to", o->to))) {
      result.code = ExitCode::Usage;
      return;
    }
    if (options.from_ms && options.to_ms && *options.to_ms <= *options.from_ms) {
      ctx.err << "seqc: error: --to must be after --from\n";
      result.code = ExitCode::Usage;
      return;
    }
    Compiled c = compile_and_report(ctx, o->file, o->strict);
    result.code = c.code;
    if (c.code != ExitCode::Ok) return;
    const std::string name = o->file == "-" ? std::string(kStdinName)
                                            : std::filesystem::path(o->file).filename().string();
    std::string svg;
    if (const compiler::ServoProgram* p = c.output.servo_program()) {
      options.title = name + ", group " + std::to_string(o->group);
      svg = backend::plot_servo_program(*p, options);
    } else if (const compiler::RaspblockProgram* car = c.output.raspblock_program()) {
      options.title = name + " (Raspblock)";
      svg = backend::plot_car_program(*car, options);
    }
    if (o->output == "-") {
      ctx.out << svg;
    } else if (auto ok = io::write_file_atomically(o->output, svg); !ok) {
      ctx.err << "seqc: error: cannot write '" << o->output << "': " << ok.error().message << "\n";
      result.code = ExitCode::FileError;
    } else {
      summarize(ctx, o->output + ": " + std::to_string(svg.size()) + " bytes");
    }
  });
}

}  // namespace seqc::cli
