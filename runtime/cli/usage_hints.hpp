// Finds what a person mistyped on the command line before CLI11's generic message would:
// an unknown subcommand or an unknown option of the subcommand it follows, with the closest
// known name ("seqc chekc" -> "unknown command 'chekc'; did you mean 'check'?").
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace seqc::cli {

// The first unknown subcommand or option in `args` (argv without the program name), as a
// complete message, or nothing if every word names something `app` knows.
std::optional<std::string> find_unknown_word(const CLI::App& app,
                                             const std::vector<std::string>& args);

// The subcommand `names` lead to from `app` ("group run"), or nullptr with `unknown` set to
// the first word that names nothing.
const CLI::App* find_subcommand(const CLI::App& app, const std::vector<std::string>& names,
                                std::string& unknown);

}  // namespace seqc::cli
