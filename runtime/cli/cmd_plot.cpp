// seqc plot FILE [-o out.svg] [--group N] [--from T] [--to T]: the program as an SVG picture
// (compiler/formats/plot_svg.hpp). Without -o the SVG goes to stdout.
#include <filesystem>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "base/units.hpp"
#include "compiler/formats/program_views.hpp"
#include "runtime/cli/board_text.hpp"
#include "runtime/cli/commands.hpp"
#include "runtime/cli/compile_report.hpp"

namespace seqc::cli {
namespace {

// "1.5s" or "500ms" (beats need the file's tempo: not here).
std::optional<double> window_ms(Context& ctx, const std::string& option, const std::string& text) {
  const std::optional<double> ms = seqc::parse_clock_ms(text);
  if (!ms) usage_error(ctx, option + " " + text + ": give a time in ms or s, e.g. 1.5s");
  return ms;
}

// A show: every performer's picture, titled with its name and file, on one time axis.
std::string plot_performers(const compiler::ShowOutput& show, const std::string& name,
                            const compiler::PlotOptions& options, seqc::SongReader* songs) {
  std::vector<compiler::ShowPart> parts;
  for (const compiler::Performer& p : show.performers) {
    parts.push_back(
        {&*p.output.program, part_title(p.output, p.name + ": " + p.file, p.group), p.name});
  }
  return compiler::plot_show(parts, name, show.name, options, songs);
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
    compiler::PlotOptions options;
    if (!o->from.empty() && !(options.from_ms = window_ms(ctx, "--from", o->from))) {
      result.code = ExitCode::Usage;
      return;
    }
    if (!o->to.empty() && !(options.to_ms = window_ms(ctx, "--to", o->to))) {
      result.code = ExitCode::Usage;
      return;
    }
    if (options.from_ms && options.to_ms && *options.to_ms <= *options.from_ms) {
      result.code = usage_error(ctx, "--to must be after --from");
      return;
    }
    const std::string name = o->file == "-" ? std::string(kStdinName)
                                            : std::filesystem::path(o->file).filename().string();
    const Loaded loaded = load_and_report(ctx, o->file, o->strict, SongCheck::Decode);
    result.code = loaded.code;
    if (result.code != ExitCode::Ok) return;
    std::string svg;
    if (loaded.file.is_show()) {
      svg = plot_performers(loaded.file.show(), name, options, ctx.songs);
    } else {
      const compiler::CompileOutput& output = loaded.file.program();
      // A file with `music:` gets its song drawn under the lanes.
      options.title = part_title(output, name, o->group);
      svg = compiler::plot_program(*output.program, options, ctx.songs);
    }
    result.code = write_output(ctx, o->output, svg, loaded.file.inputs());
    if (result.code == ExitCode::Ok && o->output != "-") {
      summarize(ctx, o->output + ": " + std::to_string(svg.size()) + " bytes");
    }
  });
}

}  // namespace seqc::cli
