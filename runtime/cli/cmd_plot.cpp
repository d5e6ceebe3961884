// seqc plot FILE [-o out.svg] [--group N] [--from T] [--to T]: the program as an SVG picture
// (compiler/formats/plot_svg.hpp). Without -o the SVG goes to stdout.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "base/units.hpp"
#include "compiler/formats/plot_svg.hpp"
#include "compiler/formats/program_views.hpp"
#include "compiler/formats/svg_text.hpp"
#include "runtime/boards/board.hpp"
#include "runtime/cli/commands.hpp"
#include "runtime/cli/compile_report.hpp"

namespace seqc::cli {
namespace {

// "1.5s" or "500ms" (beats need the file's tempo: not here).
std::optional<double> window_ms(Context& ctx, const std::string& option, const std::string& text) {
  auto t = seqc::parse_time(text);
  if (!t ||
      (t->unit != seqc::TimeUnit::Milliseconds && t->unit != seqc::TimeUnit::Seconds)) {
    ctx.err << "seqc: error: " << option << " " << text << ": give a time in ms or s, e.g. 1.5s\n";
    return std::nullopt;
  }
  return t->unit == seqc::TimeUnit::Seconds ? t->amount * 1000.0 : t->amount;
}

// The title names the group a stored program is for, else the board that plays it.
std::string titled_plot(const compiler::CompileOutput& output, const std::string& name, int group,
                        compiler::PlotOptions options) {
  const boards::Board& board = boards::board_for(output);
  options.title = board.plan != nullptr ? name + ", group " + std::to_string(group)
                                        : name + " (" + std::string(board.name) + ")";
  return compiler::plot_program(*output.program, options);
}

// A show: every performer's picture on one time axis (the longest performer's), stacked as
// nested <svg> elements in one document.
std::string plot_show(const compiler::ShowOutput& show, const std::string& name,
                      compiler::PlotOptions options) {
  double end = 0;
  for (const compiler::Performer& p : show.performers) {
    end = std::max(end, double(compiler::length_ms(*p.output.program)));
  }
  if (!options.from_ms) options.from_ms = 0;
  if (!options.to_ms) options.to_ms = end;
  std::string body;
  double y = 36;
  for (const compiler::Performer& p : show.performers) {
    std::string part = titled_plot(p.output, p.name + ": " + p.file, p.group, options);
    const auto h = part.find("height=\"");
    const double height = std::atof(part.c_str() + h + 8);
    part.insert(part.find("<svg") + 4, " y=\"" + std::to_string(static_cast<int>(y)) + "\"");
    body += part;
    y += height + 10;
  }
  return "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"1100\" height=\"" +
         std::to_string(static_cast<int>(y)) + "\" viewBox=\"0 0 1100 " +
         std::to_string(static_cast<int>(y)) + "\" font-family=\"sans-serif\">\n<title>" +
         compiler::svg::escape(name) +
         "</title>\n<rect width=\"1100\" "
         "height=\"" +
         std::to_string(static_cast<int>(y)) +
         "\" fill=\"#ffffff\"/>\n<text x=\"12\" "
         "y=\"24\" font-size=\"17\" font-weight=\"bold\">show " +
         compiler::svg::escape(show.name) + " (" + std::to_string(show.performers.size()) +
         " performers, one clock)</text>\n" + body + "</svg>\n";
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
      ctx.err << "seqc: error: --to must be after --from\n";
      result.code = ExitCode::Usage;
      return;
    }
    const std::string name = o->file == "-" ? std::string(kStdinName)
                                            : std::filesystem::path(o->file).filename().string();
    const Loaded loaded = load_and_report(ctx, o->file, o->strict, SongCheck::Decode);
    result.code = loaded.code;
    if (result.code != ExitCode::Ok) return;
    std::string svg;
    if (loaded.file.is_show()) {
      svg = plot_show(loaded.file.show(), name, options);
    } else {
      const compiler::CompileOutput& output = loaded.file.program();
      // A file with `music:` gets its song drawn under the lanes.
      std::optional<compiler::PlotSong> song;
      if (ctx.songs != nullptr) song = compiler::plot_song(*output.program, *ctx.songs);
      options.song = song ? &*song : nullptr;
      svg = titled_plot(output, name, o->group, options);
    }
    result.code = write_output(ctx, o->output, svg, inputs_of(loaded.file));
    if (result.code == ExitCode::Ok && o->output != "-") {
      summarize(ctx, o->output + ": " + std::to_string(svg.size()) + " bytes");
    }
  });
}

}  // namespace seqc::cli
