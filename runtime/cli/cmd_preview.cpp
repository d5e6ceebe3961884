// seqc preview FILE [-o dance.html] [--group N] [--strict]: the choreography (or a show's
// performers, on one clock) as one self-contained, animated HTML page
// (compiler/formats/preview_html.hpp). Without -o the page goes to stdout.
#include <algorithm>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "compiler/formats/preview_html.hpp"
#include "compiler/formats/program_views.hpp"
#include "runtime/boards/board.hpp"
#include "runtime/cli/commands.hpp"
#include "runtime/cli/compile_report.hpp"

namespace seqc::cli {
namespace {

// As `seqc plot` titles a picture: the group a stored program is for, else the board.
std::string part_title(const compiler::CompileOutput& output, const std::string& name, int group) {
  const boards::Board& board = boards::board_for(output);
  return board.plan != nullptr ? name + ", group " + std::to_string(group)
                               : name + " (" + std::string(board.name) + ")";
}

std::string preview_show(const compiler::ShowOutput& show, const std::string& name) {
  double end = 0;
  for (const compiler::Performer& p : show.performers) {
    end = std::max(end, static_cast<double>(compiler::length_ms(*p.output.program)));
  }
  std::vector<std::string> names;
  std::vector<compiler::PreviewPart> parts;
  for (const compiler::Performer& p : show.performers) {
    auto part = compiler::preview_part(
        *p.output.program,
        part_title(p.output, std::filesystem::path(p.file).filename().string(), p.group), end);
    if (!part) continue;
    names.push_back(p.name);
    parts.push_back(std::move(*part));
  }
  return compiler::preview_page("show " + show.name + " (" + std::to_string(parts.size()) +
                                   " performers, one clock), " + name,
                               names, parts, end);
}

}  // namespace

void add_preview_command(CLI::App& app, Context& ctx, Outcome& result) {
  struct Options {
    std::string file;
    std::string output = "-";
    int group = 0;
    bool strict = false;
  };
  auto o = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand(
      "preview", "Write a choreography or show as one animated, self-contained HTML page");
  cmd->add_option("FILE", o->file, "Choreography or show file (.yaml); - for stdin")->required();
  cmd->add_option("-o,--output", o->output, "Write the HTML here (default: stdout)");
  cmd->add_option("--group", o->group, "The action group it is for (0-254), shown in the title")
      ->check(CLI::Range(0, 254));
  cmd->add_flag("--strict", o->strict, "Treat warnings as errors");
  cmd->callback([&ctx, &result, o] {
    const std::string name = o->file == "-" ? std::string(kStdinName)
                                            : std::filesystem::path(o->file).filename().string();
    const Loaded loaded = load_and_report(ctx, o->file, o->strict);
    result.code = loaded.code;
    if (result.code != ExitCode::Ok) return;
    std::string html;
    if (loaded.file.is_show()) {
      html = preview_show(loaded.file.show(), name);
    } else {
      const compiler::CompileOutput& output = loaded.file.program();
      const double end = static_cast<double>(compiler::length_ms(*output.program));
      const std::string title = part_title(output, name, o->group);
      // A file with `music:` brings its song: drawn under the lanes and played with the page.
      std::optional<compiler::PlotSong> picture;
      if (ctx.songs != nullptr) picture = compiler::plot_song(*output.program, *ctx.songs);
      const std::optional<compiler::PreviewSong> song =
          compiler::preview_song(*output.program, ctx.files);
      if (auto part =
              compiler::preview_part(*output.program, title, end, picture ? &*picture : nullptr)) {
        html = compiler::preview_page(title, {""}, {std::move(*part)}, end, song ? &*song : nullptr);
      }
    }
    result.code = write_output(ctx, o->output, html, inputs_of(loaded.file));
    if (result.code == ExitCode::Ok && o->output != "-") {
      summarize(ctx, o->output + ": " + std::to_string(html.size()) + " bytes");
    }
  });
}

}  // namespace seqc::cli
