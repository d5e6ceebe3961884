// seqc import FILE.d6a [-o out.yaml] [--robot PROFILE] and
// seqc export FILE.yaml [-o out.d6a] [--group N]: Hiwonder's .d6a action files to and from
// choreographies (compiler/formats/d6a.hpp, compiler/formats/d6a_import.hpp; docs/d6a.md).
#include <filesystem>
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

void add_import_command(CLI::App& app, Context& ctx, Outcome& result) {
  struct Options {
    std::string file;
    std::string output = "-";
    std::string robot;
  };
  auto o = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand(
      "import", "Turn a Hiwonder .d6a action file into a choreography (one step per row)");
  cmd->add_option("FILE", o->file, "The .d6a file (a SQLite database); - for stdin")->required();
  cmd->add_option("-o,--output", o->output, "Write the choreography here (default: stdout)");
  cmd->add_option("--robot", o->robot,
                  "Profile to write (default: xarm for 6 servo columns, else bus)");
  cmd->callback([&ctx, &result, o] {
    auto bytes = io::read_input(o->file, ctx.files, ctx.in, kStdinName);
    if (!bytes) {
      ctx.err << "seqc: error: " << bytes.error().message << "\n";
      result.code = ExitCode::FileError;
      return;
    }
    auto table = compiler::read_d6a(*bytes);
    if (!table) {
      ctx.err << "seqc: error: " << o->file << ": " << table.error().message << "\n";
      result.code = ExitCode::InvalidInput;
      return;
    }
    compiler::ImportOptions options;
    options.source = o->file == "-" ? std::string(kStdinName)
                                    : std::filesystem::path(o->file).filename().string();
    options.name = o->file == "-" ? "imported" : std::filesystem::path(o->file).stem().string();
    options.profile = o->robot;
    auto yaml = compiler::choreography_from_d6a(*table, options);
    if (!yaml) {
      ctx.err << "seqc: error: " << o->file << ": " << yaml.error().message << "\n";
      result.code = ExitCode::InvalidInput;
      return;
    }
    result.code = write_output(ctx, o->output, *yaml, {o->file});
    if (result.code == ExitCode::Ok && o->output != "-") {
      summarize(ctx,
                o->output + ": " + std::to_string(table->rows.size()) + " steps from " + o->file);
    }
  });
}

void add_export_command(CLI::App& app, Context& ctx, Outcome& result) {
  struct Options {
    std::string file;
    std::string output;
    int group = 0;
    bool strict = false;
    ClockScaleOptions clock;
  };
  auto o = std::make_shared<Options>();
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
  cmd->callback([&ctx, &result, o] {
    std::int32_t ppm = 0;
    if (const ExitCode e = resolve_clock_ppm(ctx, o->clock, ppm); e != ExitCode::Ok) {
      result.code = e;
      return;
    }
    Compiled c = compile_and_report(ctx, o->file, o->strict, SongCheck::Skip, ppm);
    result.code = c.code;
    if (c.code != ExitCode::Ok) return;
    const compiler::ServoProgram* program = c.output.servo_program();
    if (program == nullptr) {
      ctx.err << "seqc: error: " << o->file << ": a " << boards::board_for(c.output).name
              << " program is a live stream; a .d6a file holds servo actions\n";
      result.code = ExitCode::InvalidInput;
      return;
    }
    auto table = compiler::d6a_from_program(*program);
    auto bytes = table ? compiler::write_d6a(*table) : Result<std::string>(table.error());
    if (!bytes) {
      ctx.err << "seqc: error: " << o->file << ": " << bytes.error().message << "\n";
      result.code = ExitCode::InvalidInput;
      return;
    }
    std::string out = o->output;
    if (out.empty()) {
      out = o->file == "-" ? "group" + std::to_string(o->group) + ".d6a"
                           : std::filesystem::path(o->file).stem().string() + ".d6a";
    }
    result.code = write_output(ctx, out, *bytes, c.output.inputs());
    if (result.code == ExitCode::Ok && out != "-") {
      summarize(ctx, out + ": " + std::to_string(table->rows.size()) + " actions, Servo1..Servo" +
                         std::to_string(table->servo_columns));
    }
  });
}

}  // namespace seqc::cli
