#include "runtime/cli/trace_option.hpp"

#include <ostream>

#include "runtime/cli/commands.hpp"

namespace seqc::cli {

void add_trace_option(CLI::App& cmd, std::string& path, const std::string& help) {
  cmd.add_option("--trace", path, help);
}

ExitCode open_trace(Context& ctx, boards::TraceFile& trace, const std::string& path) {
  return trace.open(path) ? ExitCode::Ok : trace_unwritable(ctx, path);
}

ExitCode trace_unwritable(Context& ctx, const std::string& path) {
  return fail(ctx, ExitCode::FileError, "--trace " + path + ": cannot write the file");
}

}  // namespace seqc::cli
