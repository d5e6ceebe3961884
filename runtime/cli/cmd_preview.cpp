// seqc preview FILE [-o dance.html] [--group N] [--strict]: the choreography (or a show's
// performers, on one clock) as one self-contained, animated HTML page
// (compiler/formats/preview_html.hpp). Without -o the page goes to stdout.
#include <filesystem>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "base/terminal_text.hpp"
#include "compiler/formats/preview_html.hpp"
#include "compiler/formats/program_views.hpp"
#include "runtime/cli/board_text.hpp"
#include "runtime/cli/commands.hpp"
#include "runtime/cli/compile_report.hpp"

namespace seqc::cli {
namespace {

// Every performer on one time axis, titled with its file's name.
std::string preview_performers(Context& ctx, const compiler::ShowOutput& show,
                               const std::string& name, std::string& missing) {
  std::vector<compiler::ShowPart> parts;
  for (const compiler::Performer& p : show.performers) {
    const std::string file = std::filesystem::path(p.file).filename().string();
    parts.push_back({&*p.output.program, part_title(p.output, file, p.group), p.name});
  }
  return compiler::preview_show(parts, name, show.name, ctx.songs, &ctx.files, &missing);
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
    std::string html, missing;
    if (loaded.file.is_show()) {
      html = preview_performers(ctx, loaded.file.show(), name, missing);
    } else {
      const compiler::CompileOutput& output = loaded.file.program();
      // A file with `music:` brings its song: drawn under the lanes and played with the page.
      html = compiler::preview_program(*output.program, part_title(output, name, o->group),
                                       ctx.songs, ctx.files, &missing);
    }
    if (!missing.empty()) ctx.err << "seqc: warning: " << terminal_safe(missing) << "\n";
    result.code = write_output(ctx, o->output, html, loaded.file.inputs());
    if (result.code == ExitCode::Ok && o->output != "-") {
      summarize(ctx, o->output + ": " + std::to_string(html.size()) + " bytes");
    }
  });
}

}  // namespace seqc::cli
