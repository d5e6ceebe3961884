// The command line as data, read from the same CLI11 tree `seqc --help` prints, so the man
// page and the shell completions generated from it cannot drift from the help text.
#pragma once

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace seqc::cli::docgen {

// What a shell should offer as an option's value.
enum class ValueKind { None, Text, File, Port, Choice };

struct OptionDoc {
  std::vector<std::string> names;  // "-o", "--output"
  std::string value_name;          // "FILE", "INT", "" for a flag
  std::string description;
  ValueKind kind = ValueKind::None;
  std::vector<std::string> choices;  // ValueKind::Choice
};

struct PositionalDoc {
  std::string name;         // "FILE"
  std::string description;  // as in --help
  std::string extension;    // "yaml yml" when the argument is a choreography file, else ""
  bool repeats = false;
  bool required = false;
};

struct CommandDoc {
  std::vector<std::string> path;  // {} for seqc, {"group", "run"} for `seqc group run`
  std::string description;
  std::vector<OptionDoc> options;  // without -h/--help
  std::vector<PositionalDoc> positionals;
  std::vector<CommandDoc> subcommands;

  std::string joined_path() const;  // "group run"
};

CommandDoc describe(const CLI::App& app);

}  // namespace seqc::cli::docgen
