// seqc simulate FILE [-o out.csv] [--step MS] [--compare]: servo positions over time as CSV;
// --compare adds the intended curve beside each servo and prints, on stderr, each servo's
// largest difference between the compiled motion and that curve. A show file gives one CSV per
// performer (their columns and sampling differ: a car's state is not a servo's position): with
// -o OUT.csv each goes to OUT-NAME.csv, on stdout each follows a "# performer NAME (FILE)" line.
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "base/units.hpp"
#include "compiler/formats/program_views.hpp"
#include "runtime/cli/commands.hpp"
#include "runtime/cli/compile_report.hpp"
#include "runtime/io/disk.hpp"

namespace seqc::cli {
namespace {

struct SimulateOptions {
  std::string file;
  std::string output;
  int step_ms = 20;
  bool step_given = false;  // without --step, a long program is sampled coarser (see below)
  bool strict = false;
  bool compare = false;
};

// Simulates one program and says so on stderr (`name` for messages); false when its kind
// cannot be simulated (said).
bool simulate_one(Context& ctx, const compiler::CompileOutput& output, const std::string& name,
                  const SimulateOptions& o, std::string& csv) {
  const std::uint32_t step = o.step_given ? static_cast<std::uint32_t>(o.step_ms)
                                          : compiler::default_simulate_step_ms(*output.program);
  const compiler::Simulated sim = compiler::simulate(*output.program, step, o.compare);
  if (!sim.ok) {
    ctx.err << "seqc: error: " << name << ": this robot kind cannot be simulated\n";
    return false;
  }
  if (o.compare && output.raspblock_program() != nullptr) {
    ctx.err << "seqc: note: " << name
            << ": --compare measures a servo controller's fitted actions against their curves; "
               "the car's packets are not compared, and the CSV has no intended curves\n";
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

ExitCode simulate_show(Context& ctx, const compiler::ShowOutput& show, const SimulateOptions& o) {
  const bool to_stdout = o.output.empty() || o.output == "-";
  const std::vector<std::string> inputs = show.inputs();
  if (!to_stdout) {
    // Every output is checked before the first is written, so a refusal writes nothing.
    for (const compiler::Performer& p : show.performers) {
      if (refuse_input_as_output(ctx, "-o", io::tagged_path(o.output, p.name), inputs)) {
        return ExitCode::Usage;
      }
    }
  }
  for (const compiler::Performer& p : show.performers) {
    std::string csv;
    if (!simulate_one(ctx, p.output, p.file + " (" + p.name + ")", o, csv)) {
      return ExitCode::InvalidInput;
    }
    if (to_stdout) {
      ctx.out << "# performer " << p.name << " (" << p.file << ")\n" << csv;
    } else if (const ExitCode c = write_output(ctx, io::tagged_path(o.output, p.name), csv, inputs);
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
  CLI::Option* step =
      cmd->add_option("--step", opts->step_ms, "Sample every this many milliseconds")
          ->check(CLI::Range(1, 60000))
          ->default_val(20);
  cmd->add_flag("--compare", opts->compare,
                "Add each servo's intended curve to the CSV and print, per servo, the largest "
                "difference from the compiled motion and when");
  cmd->add_flag("--strict", opts->strict, "Treat warnings as errors");
  cmd->callback([&ctx, &result, opts, step] {
    opts->step_given = step->count() > 0;
    const Loaded loaded = load_and_report(ctx, opts->file, opts->strict, SongCheck::Decode);
    result.code = loaded.code;
    if (result.code != ExitCode::Ok) return;
    if (loaded.file.is_show()) {
      result.code = simulate_show(ctx, loaded.file.show(), *opts);
      return;
    }
    std::string csv;
    if (!simulate_one(ctx, loaded.file.program(), opts->file, *opts, csv)) {
      result.code = ExitCode::InvalidInput;
      return;
    }
    result.code = write_output(ctx, opts->output, csv, loaded.file.inputs());
  });
}

}  // namespace seqc::cli
