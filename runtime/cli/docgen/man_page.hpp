// seqc(1) in roff man(7) macros, from the command model: every subcommand with its options and
// arguments, in the words of `--help`.
#pragma once

#include <string>

#include "runtime/cli/docgen/command_model.hpp"

namespace seqc::cli::docgen {

std::string man_page(const CommandDoc& root, const std::string& version,
                     const std::string& exit_footer);

}  // namespace seqc::cli::docgen
