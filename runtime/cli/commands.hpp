// One function per subcommand: it adds the subcommand to `app` and sets `result` when it runs;
// and the two ways every command speaks to a person: a summary, and the error that ends it.
#pragma once

#include <ostream>
#include <string>

#include "runtime/cli/context.hpp"
#include "runtime/cli/exit_codes.hpp"

namespace CLI {
class App;
}  // namespace CLI

namespace seqc::compiler {
struct CompileOutput;
}  // namespace seqc::compiler

namespace seqc::cli {

// A summary of what a command did ("group 3 erased"): on stderr after "seqc: ", like every
// message for people, and not at all with --quiet. Data (readings, listings) go to ctx.out.
inline void summarize(Context& ctx, const std::string& line) {
  if (ctx.verbosity >= 0) ctx.err << "seqc: " << line << "\n";
}

// An error that ends a command: "seqc: error: MESSAGE" on stderr, at every verbosity. Returns
// `code`, the command's exit status.
inline ExitCode fail(Context& ctx, ExitCode code, const std::string& message) {
  ctx.err << "seqc: error: " << message << "\n";
  return code;
}
// fail() for a command line that cannot run: ExitCode::Usage.
inline ExitCode usage_error(Context& ctx, const std::string& message) {
  return fail(ctx, ExitCode::Usage, message);
}

// Where a subcommand's callback stores its exit status.
struct Outcome {
  ExitCode code = ExitCode::Ok;
};

void add_check_command(CLI::App& app, Context& ctx, Outcome& result);
void add_compile_command(CLI::App& app, Context& ctx, Outcome& result);
void add_decode_command(CLI::App& app, Context& ctx, Outcome& result);
void add_simulate_command(CLI::App& app, Context& ctx, Outcome& result);
void add_emulate_command(CLI::App& app, Context& ctx, Outcome& result);
void add_ports_command(CLI::App& app, Context& ctx, Outcome& result);
void add_play_command(CLI::App& app, Context& ctx, Outcome& result);
// Servo controller commands (docs/commands.md).
void add_group_command(CLI::App& app, Context& ctx, Outcome& result);
void add_battery_command(CLI::App& app, Context& ctx, Outcome& result);
void add_servo_command(CLI::App& app, Context& ctx, Outcome& result);
void add_offset_command(CLI::App& app, Context& ctx, Outcome& result);
void add_bus_info_command(CLI::App& app, Context& ctx, Outcome& result);
void add_upload_command(CLI::App& app, Context& ctx, Outcome& result);
// `seqc calibrate clock`: the board's clock against the computer's (cmd_calibrate.cpp).
void add_calibrate_command(CLI::App& app, Context& ctx, Outcome& result);
// Hiwonder .d6a action files (cmd_d6a.cpp).
void add_import_command(CLI::App& app, Context& ctx, Outcome& result);
void add_export_command(CLI::App& app, Context& ctx, Outcome& result);
void add_teach_command(CLI::App& app, Context& ctx, Outcome& result);
void add_plot_command(CLI::App& app, Context& ctx, Outcome& result);
// An animated HTML page of a choreography or show (cmd_preview.cpp).
void add_preview_command(CLI::App& app, Context& ctx, Outcome& result);
// That page, live, served on the loopback address (cmd_studio.cpp).
void add_studio_command(CLI::App& app, Context& ctx, Outcome& result);
void add_show_command(CLI::App& app, Context& ctx, Outcome& result);
// `seqc follow`: a show's master clock drives the robot (cmd_follow.cpp).
void add_follow_command(CLI::App& app, Context& ctx, Outcome& result);
// A song's tempo map (cmd_beats.cpp).
void add_beats_command(CLI::App& app, Context& ctx, Outcome& result);
// The language server for editors (cmd_lsp.cpp).
void add_lsp_command(CLI::App& app, Context& ctx, Outcome& result);

// For `seqc upload` (cmd_play.cpp): if `output` is for a board that stores nothing (the
// Raspblock), explains on `err` that it has no storage and points to `seqc play`, and returns
// true.
bool explain_no_storage(const compiler::CompileOutput& output, const std::string& path,
                        std::ostream& err);

}  // namespace seqc::cli
