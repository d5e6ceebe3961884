#include "runtime/cli/clock_option.hpp"

#include <ostream>

#include "base/diagnostics.hpp"
#include "runtime/cli/commands.hpp"

namespace seqc::cli {

void add_clock_options(CLI::App& cmd, ClockScaleOptions& options) {
  cmd.add_option("--clock-ppm", options.clock_ppm,
                 "The board's clock error in ppm (`seqc calibrate clock`): the stored group's "
                 "times are pre-scaled so it lasts the intended time");
  cmd.add_option("--rig", options.rig,
                 "Rig file (YAML: clock_ppm, audio_offset; docs/music.md); --clock-ppm wins");
}

ExitCode read_rig(Context& ctx, const std::string& path, std::optional<compiler::Rig>& rig) {
  auto text = ctx.files.read(path);
  if (!text) return fail(ctx, ExitCode::FileError, "--rig: " + text.error().message);
  seqc::SourceManager sources;
  seqc::Diagnostics diags;
  const std::uint32_t file = sources.add(path, *text);
  rig = compiler::parse_rig(sources, file, diags);
  ctx.err << seqc::render_all(diags, sources, false, ctx.color);
  return rig ? ExitCode::Ok : ExitCode::InvalidInput;
}

ExitCode resolve_clock_ppm(Context& ctx, const ClockScaleOptions& options, std::int32_t& ppm) {
  ppm = 0;
  if (!options.rig.empty()) {
    std::optional<compiler::Rig> rig;
    if (const ExitCode e = read_rig(ctx, options.rig, rig); e != ExitCode::Ok) return e;
    if (rig->clock_ppm) ppm = *rig->clock_ppm;
  }
  if (!options.clock_ppm.empty()) {
    auto given = compiler::parse_clock_ppm(options.clock_ppm);
    if (!given) return usage_error(ctx, "--clock-ppm: " + given.error().message);
    ppm = *given;
  }
  return ExitCode::Ok;
}

}  // namespace seqc::cli
