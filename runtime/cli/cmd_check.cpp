// seqc check FILE... [--strict] [--format text|json|sarif]: with text (the default)
// diagnostics on stderr and one summary line per file on stdout: for a stored group its budget
// ("walk.yaml: 29/1020 actions, 8.000 s, fit within 0.98 units (base at 4.411 s)"), for a
// streamed program its packets and duration, else its mistakes. With json or sarif, one
// document on stdout holding every file's diagnostics (check_formats.hpp) and nothing else.
#include <string>
#include <vector>

#include <fmt/format.h>

#include "compiler/source/units.hpp"
#include "runtime/cli/check_formats.hpp"
#include "runtime/cli/commands.hpp"
#include "runtime/cli/compile_report.hpp"
#include "runtime/cli/version.hpp"
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
    std::string format = "text";
  };
  auto opts = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand("check", "Check choreography files for mistakes");
  cmd->add_option("FILE", opts->files, "Choreography files (.yaml)")->required();
  cmd->add_flag("--strict", opts->strict, "Treat warnings as errors");
  cmd->add_option("--format", opts->format,
                  "text (default), json (an array of diagnostics) or sarif (SARIF 2.1.0)")
      ->check(CLI::IsMember({"text", "json", "sarif"}));
  cmd->callback([&ctx, &result, opts] {
    if (opts->format != "text") {
      std::vector<Compiled> compiled;
      compiled.reserve(opts->files.size());
      std::vector<CheckedFile> files;
      ExitCode code = ExitCode::Ok;
      for (const std::string& path : opts->files) {
        compiled.push_back(compile_quietly(ctx, path, opts->strict));
        const Compiled& c = compiled.back();
        if (c.code == ExitCode::FileError) {
          code = ExitCode::FileError;
        } else if (c.code != ExitCode::Ok && code == ExitCode::Ok) {
          code = ExitCode::InvalidInput;
        }
      }
      for (std::size_t i = 0; i < compiled.size(); ++i) {
        files.push_back({opts->files[i] == "-" ? kStdinName : opts->files[i], &compiled[i].output});
      }
      ctx.out << (opts->format == "json" ? diagnostics_json(files, opts->strict)
                                         : diagnostics_sarif(files, opts->strict, kVersion));
      result.code = code;
      return;
    }
    bool invalid = false;
    bool unreadable = false;
    for (const std::string& given : opts->files) {
      Compiled c = compile_and_report(ctx, given, opts->strict);
      const std::string path = given == "-" ? kStdinName : given;
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
