#include "runtime/cli/realtime_option.hpp"

namespace seqc::cli {

CLI::Option* add_realtime_option(CLI::App& cmd, bool& realtime, const std::string& help,
                                 CLI::Option* needs) {
  CLI::Option* option = cmd.add_flag("--realtime", realtime, help);
  if (needs != nullptr) option->needs(needs);
  return option;
}

std::unique_ptr<io::RealtimeScope> realtime_stretch(Context& ctx, bool wanted) {
  auto scope = std::make_unique<io::RealtimeScope>(ctx.scheduler, wanted);
  if (!scope->status()) {
    ctx.err << "seqc: warning: " << scope->status().error().message
            << "; playing at normal priority\n";
  }
  return scope;
}

}  // namespace seqc::cli
