#include "runtime/cli/app.hpp"

#include <ostream>

#include <CLI/CLI.hpp>

#include "runtime/cli/commands.hpp"

namespace seqc::cli {

int run(int argc, const char* const* argv, Context& ctx) {
  CLI::App app{"seqc: compile, check and upload motion sequences for hobby servo robots", "seqc"};
  app.set_version_flag("--version", "seqc 0.1.0");
  app.require_subcommand(1);
  app.footer(
      "Exit status: 0 ok, 1 invalid input, 2 usage error, 3 port unavailable,\n"
      "4 device failure, 5 file error, 70 internal error, 130 interrupted.");

  Outcome outcome;
  add_check_command(app, ctx, outcome);
  add_compile_command(app, ctx, outcome);
  add_decode_command(app, ctx, outcome);
  add_simulate_command(app, ctx, outcome);
  add_emulate_command(app, ctx, outcome);
  add_ports_command(app, ctx, outcome);
  add_play_command(app, ctx, outcome);
  add_group_command(app, ctx, outcome);
  add_battery_command(app, ctx, outcome);
  add_servo_command(app, ctx, outcome);
  add_offset_command(app, ctx, outcome);
  add_bus_info_command(app, ctx, outcome);
  add_upload_command(app, ctx, outcome);

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
    ctx.err << "seqc: error: " << e.what() << "\n";
    return to_int(ExitCode::Usage);
  }
  return to_int(outcome.code);
}

}  // namespace seqc::cli
