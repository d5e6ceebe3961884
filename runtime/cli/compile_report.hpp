// Shared by the offline subcommands: compile one file and report on stderr the way every
// subcommand does (diagnostics, or "seqc: error: cannot read ..." for a file error).
#pragma once

#include <ostream>
#include <string>

#include "compiler/compile.hpp"
#include "compiler/source/diagnostics.hpp"
#include "runtime/cli/context.hpp"
#include "runtime/cli/exit_codes.hpp"

namespace seqc::cli {

struct Compiled {
  compiler::CompileOutput output;
  ExitCode code = ExitCode::Ok;
};

inline Compiled compile_and_report(Context& ctx, const std::string& path, bool strict) {
  Compiled c{compiler::compile_file(path, ctx.files, compiler::CompileOptions{strict})};
  if (c.output.read_error) {
    ctx.err << "seqc: error: " << *c.output.read_error << "\n";
    c.code = ExitCode::FileError;
    return c;
  }
  ctx.err << compiler::render_all(c.output.diagnostics, c.output.sources, strict);
  c.code = c.output.program ? ExitCode::Ok : ExitCode::InvalidInput;
  return c;
}

}  // namespace seqc::cli
