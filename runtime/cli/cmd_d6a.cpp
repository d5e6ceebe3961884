// seqc import FILE.d6a [-o out.yaml] [--robot PROFILE] and
// seqc export FILE.yaml [-o out.d6a] [--group N]: Hiwonder's .d6a action files to and from
// choreographies (compiler/formats/d6a.hpp, compiler/formats/d6a_import.hpp; docs/d6a.md).
#include <string>

#include <CLI/CLI.hpp>

#include "compiler/formats/d6a.hpp"
#include "compiler/formats/d6a_import.hpp"
#include "runtime/boards/board.hpp"
#include "runtime/cli/clock_option.hpp"
#include "runtime/cli/commands.hpp"
#include "runtime/cli/compile_report.hpp"
#include "runtime/io/disk.hpp"

namespace seqc::cli {

namespace {

struct ImportOptions {
  std::string file;
  std::string output = "-";
  std::string robot;
};

ExitCode run_import(Context& ctx, const ImportOptions& o) {
  auto bytes = io::read_input(o.file, ctx.files, ctx.in, kStdinName);
  if (!bytes) return fail(ctx, ExitCode::FileError, bytes.error().message);
  auto table = compiler::read_d6a(*bytes);
  if (!table) return fail(ctx, ExitCode::InvalidInput, o.file + ": " + table.error().message);
  auto yaml = compiler::choreography_from_d6a(
      *table, compiler::import_options_for(o.file, kStdinName, o.robot));
  if (!yaml) return fail(ctx, ExitCode::InvalidInput, o.file + ": " + yaml.error().message);
  const ExitCode code = write_output(ctx, o.output, *yaml, {o.file});
  if (code == ExitCode::Ok && o.output != "-") {
    summarize(ctx, o.output + ": " + std::to_string(table->rows.size()) + " steps from " + o.file);
  }
  return code;
}

struct ExportOptions {
  std::string file;
  std::string output;
  int group = 0;
  bool strict = false;
  ClockScaleOptions clock;
};

ExitCode run_export(Context& ctx, const ExportOptions& o) {
  Compiled c = compile_and_report(ctx, o.file, o.strict, SongCheck::Skip, &o.clock);
  if (c.code != ExitCode::Ok) return c.code;
  const compiler::ServoProgram* program = c.output.servo_program();
  if (program == nullptr) {
    return fail(ctx, ExitCode::InvalidInput,
                o.file + ": a " + std::string(boards::board_for(c.output).name) +
                    " program is a live stream; a .d6a file holds servo actions");
  }
  auto table = compiler::d6a_from_program(*program);
  auto bytes = table ? compiler::write_d6a(*table) : Result<std::string>(table.error());
  if (!bytes) return fail(ctx, ExitCode::InvalidInput, o.file + ": " + bytes.error().message);
  const std::string out = o.output.empty() ? compiler::d6a_output_name(o.file, o.group) : o.output;
  const ExitCode code = write_output(ctx, out, *bytes, c.output.inputs());
  if (code == ExitCode::Ok && out != "-") {
    summarize(ctx, out + ": " + std::to_string(table->rows.size()) + " actions, Servo1..Servo" +
                       std::to_string(table->servo_columns));
  }
  return code;
}

}  // namespace

void add_import_command(CLI::App& app, Context& ctx, Outcome& result) {
  auto o = std::make_shared<ImportOptions>();
  CLI::App* cmd = app.add_subcommand(
      "import", "Turn a Hiwonder .d6a action file into a choreography (one step per row)");
  cmd->add_option("FILE", o->file, "The .d6a file (a SQLite database); - for stdin")->required();
  cmd->add_option("-o,--output", o->output, "Write the choreography here (default: stdout)");
  cmd->add_option("--robot", o->robot,
                  "Profile to write (default: xarm for 6 servo columns, else bus)");
  cmd->callback([&ctx, &result, o] { result.code = run_import(ctx, *o); });
}

void add_export_command(CLI::App& app, Context& ctx, Outcome& result) {
  auto o = std::make_shared<ExportOptions>();
  CLI::App* cmd = app.add_subcommand(
      "export", "Write a choreography's compiled actions as a Hiwonder .d6a action file");
  cmd->add_option("FILE", o->file, "Choreography file (.yaml); - for stdin")->required();
  cmd->add_option("-o,--output", o->output,
                  "Write the .d6a here (default: FILE's name with .d6a, in this folder)");
  cmd->add_option("--group", o->group,
                  "The action group the file is for (0-254); a .d6a holds no group number, so "
                  "it only names the default output, groupN.d6a, when FILE is -")
      ->check(CLI::Range(0, 254));
  cmd->add_flag("--strict", o->strict, "Treat warnings as errors");
  add_clock_options(*cmd, o->clock);
  cmd->callback([&ctx, &result, o] { result.code = run_export(ctx, *o); });
}

}  // namespace seqc::cli
