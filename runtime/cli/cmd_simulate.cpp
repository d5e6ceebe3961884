// seqc simulate FILE [-o out.csv] [--step MS] [--compare]: servo positions over time as CSV;
// --compare adds the intended curve beside each servo and prints, on stderr, each servo's
// largest difference between the compiled motion and that curve. A show file gives one CSV per
// performer (their columns and sampling differ: a car's state is not a servo's position): with
// -o OUT.csv each goes to OUT-NAME.csv, on stdout each follows a "# performer NAME (FILE)" line.
#include <string>

#include <CLI/CLI.hpp>

#include "base/units.hpp"
#include "compiler/show.hpp"
#include "runtime/boards/program_views.hpp"
#include "runtime/cli/commands.hpp"
#include "runtime/cli/compile_report.hpp"
#include "runtime/io/disk.hpp"

namespace seqc::cli {
namespace {

struct SimulateOptions {
  std::string file;
  std::string output;
  int step_ms = 20;
  bool strict = false;
  bool compare = false;
};

// Simulates one program and says so on stderr (`name` for messages); false when its kind
// cannot be simulated (said).
bool simulate_one(Context& ctx, const compiler::CompileOutput& output, const std::string& name,
                  const SimulateOptions& o, std::string& csv) {
  const boards::Simulated sim =
      boards::simulate(output, static_cast<std::uint32_t>(o.step_ms), o.compare);
  if (!sim.ok) {
    ctx.err << "seqc: error: " << name << ": this robot kind cannot be simulated\n";
    return false;
  }
  for (const compiler::Difference& d : sim.differences) {
    ctx.err << "seqc: " << d.servo << ": largest difference " << seqc::format_units(d.largest)
            << " units at " << seqc::format_seconds(d.at_ms) << "\n";
  }
  ctx.err << "seqc: " << name << ": " << sim.steps << " " << sim.steps_are << ", "
          << seqc::format_seconds(sim.duration_ms) << "\n";
  csv = sim.csv;
  return true;
}

// "out.csv" and "arm" -> "out-arm.csv"; "out" -> "out-arm".
std::string performer_path(const std::string& output, const std::string& name) {
  const std::size_t slash = output.find_last_of('/');
  const std::size_t dot = output.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) {
    return output + "-" + name;
  }
  return output.substr(0, dot) + "-" + name + output.substr(dot);
}

ExitCode write_csv(Context& ctx, const std::string& path, const std::string& csv) {
  if (auto written = io::write_file_atomically(path, csv); !written) {
    ctx.err << "seqc: error: " << written.error().message << "\n";
    return ExitCode::FileError;
  }
  return ExitCode::Ok;
}

ExitCode simulate_show(Context& ctx, const SimulateOptions& o) {
  ExitCode loaded = ExitCode::Ok;
  compiler::ShowOutput show = load_show_and_report(ctx, o.file, o.strict, loaded);
  if (loaded != ExitCode::Ok) return loaded;
  const bool to_stdout = o.output.empty() || o.output == "-";
  for (const compiler::Performer& p : show.performers) {
    std::string csv;
    if (!simulate_one(ctx, p.output, p.file + " (" + p.name + ")", o, csv)) {
      return ExitCode::InvalidInput;
    }
    if (to_stdout) {
      ctx.out << "# performer " << p.name << " (" << p.file << ")\n" << csv;
    } else if (const ExitCode c = write_csv(ctx, performer_path(o.output, p.name), csv);
               c != ExitCode::Ok) {
      return c;
    }
  }
  return ExitCode::Ok;
}

}  // namespace

void add_simulate_command(CLI::App& app, Context& ctx, Outcome& result) {
  auto opts = std::make_shared<SimulateOptions>();
  CLI::App* cmd = app.add_subcommand(
      "simulate", "Print each servo's position (or the car's state) over time, as CSV");
  cmd->add_option("FILE", opts->file, "Choreography file (.yaml), or a show file")->required();
  cmd->add_option("-o,--output", opts->output,
                  "Write the CSV here instead of stdout (- is stdout); a show writes one per "
                  "performer, OUT-NAME.csv");
  cmd->add_option("--step", opts->step_ms, "Sample every this many milliseconds")
      ->check(CLI::Range(1, 60000))
      ->default_val(20);
  cmd->add_flag("--compare", opts->compare,
                "Add each servo's intended curve to the CSV and print, per servo, the largest "
                "difference from the compiled motion and when");
  cmd->add_flag("--strict", opts->strict, "Treat warnings as errors");
  cmd->callback([&ctx, &result, opts] {
    if (opts->file != "-" && compiler::is_show_file(ctx.files, opts->file)) {
      result.code = simulate_show(ctx, *opts);
      return;
    }
    Compiled c = compile_and_report(ctx, opts->file, opts->strict, SongCheck::Decode);
    result.code = c.code;
    if (!c.output.program) return;
    std::string csv;
    if (!simulate_one(ctx, c.output, opts->file, *opts, csv)) {
      result.code = ExitCode::InvalidInput;
      return;
    }
    if (opts->output.empty() || opts->output == "-") {
      ctx.out << csv;
    } else {
      result.code = write_csv(ctx, opts->output, csv);
    }
  });
}

}  // namespace seqc::cli
