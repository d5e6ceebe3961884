// Shell completions for bash, zsh and fish, from the command model: subcommands, options (with
// their choices), --port from `seqc ports --names` plus the emulators, and choreography files
// by extension.
#pragma once

#include <string>

#include "runtime/cli/docgen/command_model.hpp"

namespace seqc::cli::docgen {

std::string bash_completion(const CommandDoc& root);
std::string zsh_completion(const CommandDoc& root);
std::string fish_completion(const CommandDoc& root);

}  // namespace seqc::cli::docgen
