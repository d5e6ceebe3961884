// seqc check FILE... [--strict] [--format text|json|sarif] [--port P]: with text (the default)
// diagnostics on stderr and one summary line per file on stdout: for a stored group its budget
// ("walk.yaml: 29/1020 actions, 8.000 s, fit within 0.98 units (base at 4.411 s)", with
// `path: line` moves "... and 0.99 mm (tip at 2.379 s)"), for a
// streamed program its packets and duration, else its mistakes. With json or sarif, one
// document on stdout with every file's diagnostics (base/diagnostic_formats.hpp), nothing else.
#include <string>
#include <vector>

#include <fmt/format.h>

#include <CLI/CLI.hpp>

#include "base/diagnostic_formats.hpp"
#include "base/terminal_text.hpp"
#include "base/units.hpp"
#include "runtime/boards/board.hpp"
#include "runtime/cli/clock_option.hpp"
#include "runtime/cli/commands.hpp"
#include "runtime/cli/compile_report.hpp"
#include "runtime/cli/counted.hpp"
#include "runtime/cli/version.hpp"

namespace seqc::cli {
namespace {

// One thing checked: a choreography; or a show file's own part, then each performer's file.
struct Unit {
  std::string path;
  std::string label;  // how the summary names it
  Compiled compiled;
  bool show = false;  // the show file's own part
  std::size_t performers = 0;
};

std::vector<Unit> units_of(Context& ctx, const std::string& given, bool strict,
                           std::int32_t clock_ppm, bool over_hid) {
  std::vector<Unit> out;
  const std::string shown = given == "-" ? kStdinName : given;
  Loaded loaded = load_quietly(ctx, given, strict, SongCheck::Decode, clock_ppm, over_hid);
  if (!loaded.file.is_show()) {
    out.push_back({shown, shown, {std::move(loaded.file.program()), loaded.code}, false, 0});
    return out;
  }
  compiler::ShowOutput& show = loaded.file.show();
  Unit self{shown, shown, {}, true, show.performers.size()};
  self.compiled.output.sources = std::move(show.sources);
  self.compiled.output.diagnostics = std::move(show.diagnostics);
  self.compiled.code =
      self.compiled.output.diagnostics.has_errors(strict) ? ExitCode::InvalidInput : ExitCode::Ok;
  out.push_back(std::move(self));
  for (compiler::Performer& p : show.performers) {
    if (p.output.read_error) continue;  // reported in the show file, where it is named
    Unit u{p.file, p.file + " (" + p.name + ")", {}, false, 0};
    u.compiled.code = p.output.program ? ExitCode::Ok : ExitCode::InvalidInput;
    u.compiled.output = std::move(p.output);
    out.push_back(std::move(u));
  }
  return out;
}

// The summary line of a unit (text form).
std::string summary(const Unit& u, bool strict) {
  const seqc::Diagnostics& d = u.compiled.output.diagnostics;
  const std::string label = terminal_safe(u.label);
  const std::string warned =
      d.warning_count() ? ", " + plural(d.warning_count(), "warning") : std::string();
  if (u.show && u.compiled.code == ExitCode::Ok) {
    return fmt::format("{}: show with {}{}\n", label, plural(u.performers, "performer"), warned);
  }
  if (const compiler::RaspblockProgram* car = u.compiled.output.raspblock_program()) {
    return fmt::format("{}: ok ({}, {}){}\n", label, plural(car->packets.size(), "packet"),
                       seqc::format_seconds(car->duration_ms), warned);
  }
  if (const compiler::ServoProgram* p = u.compiled.output.servo_program()) {
    // The group's budget: actions used, duration, and the largest distance between the
    // compiled motion and the intended curve, with where it is: in units of the servos' own
    // curves, and in mm of the tip on `path: line` moves (whose joints' pieces are exact, so
    // the units alone would say 0 of them). The units are left out beside the tip's mm when
    // they are 0.
    const std::string units =
        p->fit_error > 0
            ? fmt::format("{} units ({} at {:.3f} s)", seqc::format_units(p->fit_error),
                          terminal_safe(p->fit_error_servo), p->fit_error_at_ms / 1000.0)
            : "0 units";
    std::string fit = units;
    if (p->tip_error_mm) {
      const std::string tip =
          fmt::format("{} mm (tip at {:.3f} s)", seqc::format_units(*p->tip_error_mm),
                      p->tip_error_at_ms / 1000.0);
      fit = p->fit_error > 0 ? units + " and " + tip : tip;
    }
    // A longer dance: the groups `upload --run` stores and starts one after another.
    const std::string actions =
        p->group_bars.empty()
            ? fmt::format("{}/{} actions", p->keyframes.size(), p->group_capacity)
            : fmt::format("{} actions in {} groups of at most {} (the board stores {})",
                          p->keyframes.size(), p->group_bars.size(), p->group_capacity, p->groups);
    return fmt::format("{}: {}, {:.3f} s, fit within {}{}\n", label, actions,
                       static_cast<double>(p->duration_ms()) / 1000.0, fit, warned);
  }
  const std::size_t errors = d.error_count() + (strict ? d.warning_count() : 0);
  const std::size_t warnings = strict ? 0 : d.warning_count();
  return fmt::format("{}: {}{}\n", label, plural(errors, "error"),
                     warnings ? ", " + plural(warnings, "warning") : "");
}

}  // namespace

void add_check_command(CLI::App& app, Context& ctx, Outcome& result) {
  struct Options {
    std::vector<std::string> files;
    bool strict = false;
    std::string format = "text";
    ClockScaleOptions clock;
    std::string port;
  };
  auto opts = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand("check", "Check choreography (or show) files for mistakes");
  cmd->add_option("FILE", opts->files, "Choreography files (.yaml), or show files")->required();
  cmd->add_flag("--strict", opts->strict, "Treat warnings as errors");
  cmd->add_option("--format", opts->format,
                  "text (default), json (an array of diagnostics) or sarif (SARIF 2.1.0)")
      ->check(CLI::IsMember({"text", "json", "sarif"}));
  add_clock_options(*cmd, opts->clock);
  add_link_port_option(*cmd, opts->port);
  cmd->callback([&ctx, &result, opts] {
    std::int32_t ppm = 0;
    if (const ExitCode e = resolve_clock_ppm(ctx, opts->clock, ppm); e != ExitCode::Ok) {
      result.code = e;
      return;
    }
    const bool over_hid = boards::port_over_hid(opts->port);
    std::vector<Unit> units;
    for (const std::string& given : opts->files) {
      for (Unit& u : units_of(ctx, given, opts->strict, ppm, over_hid))
        units.push_back(std::move(u));
    }
    bool invalid = false;
    bool unreadable = false;
    for (const Unit& u : units) {
      unreadable = unreadable || u.compiled.code == ExitCode::FileError;
      invalid = invalid || u.compiled.code == ExitCode::InvalidInput;
    }
    result.code =
        unreadable ? ExitCode::FileError : (invalid ? ExitCode::InvalidInput : ExitCode::Ok);
    if (opts->format != "text") {
      std::vector<CheckedFile> files;
      for (const Unit& u : units) {
        const compiler::CompileOutput& o = u.compiled.output;
        files.push_back(CheckedFile{u.path, &o.sources, &o.diagnostics, o.read_error});
      }
      ctx.out << (opts->format == "json" ? diagnostics_json(files, opts->strict)
                                         : diagnostics_sarif(files, opts->strict, kVersion));
      return;
    }
    for (const Unit& u : units) {
      const compiler::CompileOutput& out = u.compiled.output;
      if (out.read_error) {
        ctx.err << "seqc: error: " << terminal_safe(*out.read_error) << "\n";
        continue;
      }
      ctx.err << seqc::render_all(out.diagnostics, out.sources, opts->strict, ctx.color);
      ctx.out << summary(u, opts->strict);
    }
  });
}

}  // namespace seqc::cli
