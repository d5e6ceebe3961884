#include "runtime/cli/app.hpp"

#include <cerrno>
#include <new>
#include <ostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "runtime/cli/commands.hpp"
#include "runtime/cli/compile_report.hpp"
#include "runtime/cli/usage_hints.hpp"
#include "runtime/cli/version.hpp"

namespace seqc::cli {
namespace {

constexpr const char* kExitFooter =
    "Exit status: 0 ok, 1 invalid input, 2 usage error, 3 port unavailable,\n"
    "4 device failure, 5 file error, 70 internal error, 130 interrupted.";

// `seqc help [SUBCOMMAND...]`: the same text as `seqc [SUBCOMMAND...] --help`.
void add_help_command(CLI::App& app, Context& ctx, Outcome& result) {
  auto topic = std::make_shared<std::vector<std::string>>();
  CLI::App* cmd =
      app.add_subcommand("help", "Print the help of seqc or of a subcommand (seqc help group run)");
  cmd->add_option("SUBCOMMAND", *topic, "The subcommand to explain");
  cmd->callback([&app, &ctx, &result, topic] {
    std::string unknown;
    const CLI::App* target = find_subcommand(app, *topic, unknown);
    if (target == nullptr) {
      result.code = usage_error(ctx, unknown);
      return;
    }
    // make_help, not help(): help() would describe the selected subcommand, `help` itself.
    // The usage line names the whole path ("seqc group run"), as --help does.
    std::string usage_name;
    for (const CLI::App* a = target; a != nullptr; a = a->get_parent()) {
      usage_name = a->get_name() + (usage_name.empty() ? "" : " " + usage_name);
    }
    ctx.out << target->get_formatter()->make_help(target, usage_name, CLI::AppFormatMode::Normal);
    result.code = ExitCode::Ok;
  });
}

// --color: "auto" colours diagnostics when stderr is a terminal and NO_COLOR is unset.
bool wants_color(const std::string& mode, const Context& ctx) {
  if (mode == "always") return true;
  if (mode == "never") return false;
  return ctx.err_is_terminal && !ctx.no_color_env;
}

}  // namespace

void build_app(CLI::App& app, Context& ctx, Outcome& outcome) {
  app.set_version_flag("--version", std::string("seqc ") + kVersion);
  app.require_subcommand(1);
  app.fallthrough();  // global options may also follow the subcommand
  app.footer(kExitFooter);
  auto color = std::make_shared<std::string>("auto");
  auto quiet = std::make_shared<bool>(false);
  auto verbose = std::make_shared<bool>(false);
  app.add_flag("-q,--quiet", *quiet, "Print only errors and data (no progress or summaries)");
  app.add_flag("-v,--verbose", *verbose, "Also report every re-send, restart and probe");
  app.add_option("--color", *color,
                 "Colour in diagnostics: auto (a terminal without NO_COLOR), "
                 "always or never")
      ->check(CLI::IsMember({"auto", "always", "never"}));
  app.parse_complete_callback([&ctx, color, quiet, verbose] {
    ctx.verbosity = *quiet ? -1 : (*verbose ? 1 : 0);
    ctx.color = wants_color(*color, ctx);
  });

  add_check_command(app, ctx, outcome);
  add_compile_command(app, ctx, outcome);
  add_decode_command(app, ctx, outcome);
  add_simulate_command(app, ctx, outcome);
  add_plot_command(app, ctx, outcome);
  add_preview_command(app, ctx, outcome);
  add_studio_command(app, ctx, outcome);
  add_emulate_command(app, ctx, outcome);
  add_ports_command(app, ctx, outcome);
  add_play_command(app, ctx, outcome);
  add_group_command(app, ctx, outcome);
  add_battery_command(app, ctx, outcome);
  add_servo_command(app, ctx, outcome);
  add_offset_command(app, ctx, outcome);
  add_bus_info_command(app, ctx, outcome);
  add_upload_command(app, ctx, outcome);
  add_calibrate_command(app, ctx, outcome);
  add_import_command(app, ctx, outcome);
  add_export_command(app, ctx, outcome);
  add_teach_command(app, ctx, outcome);
  add_show_command(app, ctx, outcome);
  add_follow_command(app, ctx, outcome);
  add_beats_command(app, ctx, outcome);
  add_lsp_command(app, ctx, outcome);
  add_help_command(app, ctx, outcome);
}

namespace {

int run_command_line(int argc, const char* const* argv, Context& ctx) {
  CLI::App app{kAppDescription, "seqc"};
  Outcome outcome;
  build_app(app, ctx, outcome);

  std::vector<std::string> args(argv + (argc > 0 ? 1 : 0), argv + argc);
  if (auto unknown = find_unknown_word(app, args)) {
    ctx.err << "seqc: error: " << *unknown << "\n"
            << "seqc: run 'seqc help' for the list of commands and options\n";
    return to_int(ExitCode::Usage);
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    ctx.out << app.help();
    return to_int(ExitCode::Ok);
  } catch (const CLI::CallForAllHelp& e) {
    ctx.out << app.help("", CLI::AppFormatMode::All);
    return to_int(ExitCode::Ok);
  } catch (const CLI::CallForVersion& e) {
    ctx.out << e.what() << "\n";
    return to_int(ExitCode::Ok);
  } catch (const CLI::ParseError& e) {
    // Point at the help of the subcommand that was being parsed ("seqc help group run").
    std::string path;
    for (const CLI::App* a = &app; !a->get_subcommands().empty();) {
      a = a->get_subcommands().front();
      path += " " + a->get_name();
    }
    ctx.err << "seqc: error: " << e.what() << "\n"
            << "seqc: run 'seqc help" << path << "' for "
            << (path.empty() ? "the list of commands and options" : "its options") << "\n";
    return to_int(ExitCode::Usage);
  }
  return to_int(outcome.code);
}

// Data written to stdout is only known written once flushed: a full disk or a closed pipe
// shows here. A command that failed already keeps its status (and its own message).
int finish_stdout(Context& ctx, int code) {
  errno = 0;
  if (ctx.out.flush()) return code;
  if (code != to_int(ExitCode::FileError)) say_stdout_failed(ctx, errno);
  return code == to_int(ExitCode::Ok) ? to_int(ExitCode::FileError) : code;
}

}  // namespace

int run(int argc, const char* const* argv, Context& ctx) {
  int code = to_int(ExitCode::Internal);
  try {
    code = run_command_line(argc, argv, ctx);
  } catch (const std::bad_alloc&) {
    // A file or a song too large for this machine: said plainly, not an abort and a core.
    ctx.err << "seqc: error: out of memory\n";
    return to_int(ExitCode::Internal);
  }
  return finish_stdout(ctx, code);
}

}  // namespace seqc::cli
