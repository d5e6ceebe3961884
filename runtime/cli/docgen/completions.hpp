// Shell completions for bash, zsh and fish, from the command model: subcommands, options (with
// their choices), --port from `seqc ports --names` plus the emulators, and choreography files
// by extension.
#pragma once

#include <string>
#include <vector>

#include "runtime/cli/docgen/command_model.hpp"

namespace seqc::cli::docgen {

std::string bash_completion(const CommandDoc& root);
std::string zsh_completion(const CommandDoc& root);
std::string fish_completion(const CommandDoc& root);

// The words one after the other, a space between each: a shell's word list.
inline std::string space_separated(const std::vector<std::string>& list) {
  std::string out;
  for (const std::string& w : list) out += (out.empty() ? "" : " ") + w;
  return out;
}

}  // namespace seqc::cli::docgen
