// seqc-docgen man|bash|zsh|fish: prints seqc's man page or a shell completion, generated from
// the command line seqc itself builds (build_app), so neither can drift from `seqc --help`.
// Run by the build; not installed.
#include <iostream>
#include <sstream>
#include <string>

#include <CLI/CLI.hpp>

#include "runtime/cli/app.hpp"
#include "runtime/cli/commands.hpp"
#include "runtime/cli/docgen/command_model.hpp"
#include "runtime/cli/docgen/completions.hpp"
#include "runtime/cli/docgen/man_page.hpp"
#include "runtime/cli/version.hpp"
#include "runtime/io/clock.hpp"
#include "runtime/io/disk.hpp"

int main(int argc, char** argv) {
  const std::string what = argc == 2 ? argv[1] : "";
  std::ostringstream sink;
  seqc::io::SteadyClock clock;
  seqc::io::DiskFileReader files;
  seqc::cli::Context ctx{sink, sink, clock, files};
  seqc::cli::Outcome outcome;
  CLI::App app{seqc::cli::kAppDescription, "seqc"};
  seqc::cli::build_app(app, ctx, outcome);
  const seqc::cli::docgen::CommandDoc root = seqc::cli::docgen::describe(app);
  if (what == "man") {
    std::cout << seqc::cli::docgen::man_page(root, seqc::cli::kVersion, app.get_footer());
  } else if (what == "bash") {
    std::cout << seqc::cli::docgen::bash_completion(root);
  } else if (what == "zsh") {
    std::cout << seqc::cli::docgen::zsh_completion(root);
  } else if (what == "fish") {
    std::cout << seqc::cli::docgen::fish_completion(root);
  } else {
    std::cerr << "usage: seqc-docgen man|bash|zsh|fish\n";
    return 2;
  }
  return 0;
}
