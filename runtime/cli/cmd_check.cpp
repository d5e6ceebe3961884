// seqc check FILE... [--strict]: diagnostics on stderr, one summary line per file on stdout:
// for a stored group its budget ("walk.yaml: 29/1020 actions, 8.000 s, fit within 0.98 units
// (base at 4.411 s)"), for a streamed program its packets and duration, else its mistakes.
#include <string>
#include <vector>

#include <fmt/format.h>

#include "compiler/source/units.hpp"
#include "runtime/cli/commands.hpp"
#include "runtime/cli/compile_report.hpp"
#include "runtime/protocol/group_download.hpp"

namespace seqc::cli {
namespace {

std::string plural(std::size_t n, const char* word) {
  return fmt::format("{} {}{}", n, word, n == 1 ? "" : "s");
}

}  // namespace

void add_check_command(CLI::App& app, Context& ctx, Outcome& result) {
  struct Options {
    std::vector<std::string> files;
    bool strict = false;
  };
  auto opts = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand("check", "Check choreography files for mistakes");
  cmd->add_option("FILE", opts->files, "Choreography files (.yaml)")->required();
  cmd->add_flag("--strict", opts->strict, "Treat warnings as errors");
  cmd->callback([&ctx, &result, opts] {
    bool invalid = false;
    bool unreadable = false;
    for (const std::string& path : opts->files) {
      Compiled c = compile_and_report(ctx, path, opts->strict);
      if (c.code == ExitCode::FileError) {
        unreadable = true;
        continue;
      }
      const compiler::Diagnostics& d = c.output.diagnostics;
      if (const compiler::RaspblockProgram* car = c.output.raspblock_program()) {
        ctx.out << fmt::format(
            "{}: ok ({}, {}){}\n", path, plural(car->packets.size(), "packet"),
            compiler::format_seconds(car->duration_ms),
            d.warning_count() ? ", " + plural(d.warning_count(), "warning") : "");
      } else if (const compiler::ServoProgram* p = c.output.servo_program()) {
        // The group's budget: actions used, duration, and the largest distance between the
        // compiled motion and the intended curve, with where it is.
        const std::string where =
            p->fit_error > 0
                ? fmt::format(" ({} at {:.3f} s)", p->fit_error_servo, p->fit_error_at_ms / 1000.0)
                : "";
        ctx.out << fmt::format(
            "{}: {}/{} actions, {:.3f} s, fit within {} units{}{}\n", path, p->keyframes.size(),
            lsc::kMaxActions, static_cast<double>(p->duration_ms()) / 1000.0,
            compiler::format_units(p->fit_error), where,
            d.warning_count() ? ", " + plural(d.warning_count(), "warning") : "");
      } else {
        invalid = true;
        const std::size_t errors = d.error_count() + (opts->strict ? d.warning_count() : 0);
        const std::size_t warnings = opts->strict ? 0 : d.warning_count();
        ctx.out << fmt::format("{}: {}{}\n", path, plural(errors, "error"),
                               warnings ? ", " + plural(warnings, "warning") : "");
      }
    }
    result.code =
        unreadable ? ExitCode::FileError : (invalid ? ExitCode::InvalidInput : ExitCode::Ok);
  });
}

}  // namespace seqc::cli
