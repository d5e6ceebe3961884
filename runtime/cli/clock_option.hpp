// `--clock-ppm N` and `--rig FILE` for the commands that compile for a board (compile, upload,
// export, check): the board's clock error the compiler pre-scales the stored group's action
// times by (compiler::CompileOptions::clock_ppm). --clock-ppm wins over the rig file's
// clock_ppm. The rig file is read through ctx.files and its mistakes are reported like a
// choreography's (rig_file.hpp); its audio_offset is the music commands' (music_play.hpp).
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "compiler/frontend/rig_file.hpp"
#include "runtime/cli/context.hpp"
#include "runtime/cli/exit_codes.hpp"

namespace seqc::cli {

struct ClockScaleOptions {
  std::string clock_ppm;  // "" = not given
  std::string rig;        // "" = none
};
void add_clock_options(CLI::App& cmd, ClockScaleOptions& options);

// The rig file at `path`, read and parsed: Ok, FileError (unreadable, said on ctx.err) or
// InvalidInput (its mistakes, rendered on ctx.err).
ExitCode read_rig(Context& ctx, const std::string& path, std::optional<compiler::Rig>& rig);

// The ppm to compile with (0 when neither option is given). Ok, or: Usage (a bad --clock-ppm),
// FileError (the rig file cannot be read), InvalidInput (the rig file has mistakes, rendered on
// ctx.err).
ExitCode resolve_clock_ppm(Context& ctx, const ClockScaleOptions& options, std::int32_t& ppm);

}  // namespace seqc::cli
