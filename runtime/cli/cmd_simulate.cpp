// seqc simulate FILE [-o out.csv] [--step MS] [--compare]: servo positions over time as CSV;
// --compare adds the intended curve beside each servo and prints, on stderr, each servo's
// largest difference between the compiled motion and that curve.
#include <string>

#include "compiler/source/units.hpp"
#include "runtime/boards/program_views.hpp"
#include "runtime/cli/commands.hpp"
#include "runtime/cli/compile_report.hpp"
#include "runtime/io/disk.hpp"

namespace seqc::cli {

void add_simulate_command(CLI::App& app, Context& ctx, Outcome& result) {
  struct Options {
    std::string file;
    std::string output;
    int step_ms = 20;
    bool strict = false;
    bool compare = false;
  };
  auto opts = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand(
      "simulate", "Print each servo's position (or the car's state) over time, as CSV");
  cmd->add_option("FILE", opts->file, "Choreography file (.yaml)")->required();
  cmd->add_option("-o,--output", opts->output,
                  "Write the CSV here instead of stdout (- is stdout)");
  cmd->add_option("--step", opts->step_ms, "Sample every this many milliseconds")
      ->check(CLI::Range(1, 60000))
      ->default_val(20);
  cmd->add_flag("--compare", opts->compare,
                "Add each servo's intended curve to the CSV and print, per servo, the largest "
                "difference from the compiled motion and when");
  cmd->add_flag("--strict", opts->strict, "Treat warnings as errors");
  cmd->callback([&ctx, &result, opts] {
    Compiled c = compile_and_report(ctx, opts->file, opts->strict);
    result.code = c.code;
    if (!c.output.program) return;
    const boards::Simulated sim =
        boards::simulate(c.output, static_cast<std::uint32_t>(opts->step_ms), opts->compare);
    if (!sim.ok) {
      ctx.err << "seqc: error: " << opts->file << ": this robot kind cannot be simulated\n";
      result.code = ExitCode::InvalidInput;
      return;
    }
    for (const backend::Difference& d : sim.differences) {
      ctx.err << "seqc: " << d.servo << ": largest difference " << compiler::format_units(d.largest)
              << " units at " << compiler::format_seconds(d.at_ms) << "\n";
    }
    ctx.err << "seqc: " << opts->file << ": " << sim.steps << " " << sim.steps_are << ", "
            << compiler::format_seconds(sim.duration_ms) << "\n";
    if (opts->output.empty() || opts->output == "-") {
      ctx.out << sim.csv;
    } else if (auto written = io::write_file_atomically(opts->output, sim.csv); !written) {
      ctx.err << "seqc: error: " << written.error().message << "\n";
      result.code = ExitCode::FileError;
    }
  });
}

}  // namespace seqc::cli
