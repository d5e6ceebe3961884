#include "runtime/cli/usage_hints.hpp"

#include <cctype>

#include "base/diagnostics.hpp"

namespace seqc::cli {
namespace {

std::vector<std::string> subcommand_names(const CLI::App& app) {
  std::vector<std::string> names;
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; })) {
    names.push_back(sub->get_name());
  }
  return names;
}

// Long and short option names of `app` and of every parent (global options fall through).
std::vector<std::string> option_names(const CLI::App* app) {
  std::vector<std::string> names;
  for (; app != nullptr; app = app->get_parent()) {
    for (const CLI::Option* o : app->get_options()) {
      for (const std::string& l : o->get_lnames()) names.push_back("--" + l);
      for (const std::string& s : o->get_snames()) names.push_back("-" + s);
    }
  }
  return names;
}

const CLI::App* child(const CLI::App& app, const std::string& name) {
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; })) {
    if (sub->check_name(name)) return sub;
  }
  return nullptr;
}

// The option `name` of `app` or of a parent (global options fall through); nullptr if none.
const CLI::Option* find_option(const CLI::App* app, const std::string& name) {
  for (; app != nullptr; app = app->get_parent()) {
    if (const CLI::Option* o = app->get_option_no_throw(name)) return o;
  }
  return nullptr;
}

std::string with_hint(std::string message, const std::string& suggestion) {
  if (!suggestion.empty()) message += "; did you mean '" + suggestion + "'?";
  return message;
}

}  // namespace

std::optional<std::string> find_unknown_word(const CLI::App& app,
                                             const std::vector<std::string>& args) {
  const CLI::App* current = &app;
  bool positional_seen = false;  // after a subcommand's own argument, words are values
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& word = args[i];
    if (word == "--") break;
    // "-20" is a negative number (an offset), not an option.
    const bool number =
        word.size() > 1 && (std::isdigit(static_cast<unsigned char>(word[1])) || word[1] == '.');
    if (word.size() > 1 && word[0] == '-' && !number) {
      const std::string name = word.substr(0, word.find('='));
      // Short options may be bundled ("-qv") or carry a value ("-o-"); check the first letter.
      const std::string key = name[1] == '-' ? name : name.substr(0, 2);
      const CLI::Option* option = find_option(current, key);
      if (option == nullptr) {
        std::string title = current == &app ? "seqc" : "seqc " + current->get_name();
        return with_hint("unknown option '" + name + "' for '" + title + "'",
                         seqc::did_you_mean(name, option_names(current)));
      }
      // An option that takes a value: the next word is its value, not a subcommand.
      if (word.find('=') == std::string::npos && name == key && option->get_expected_max() > 0) {
        ++i;
      }
      continue;
    }
    if (positional_seen) continue;
    if (const CLI::App* sub = child(*current, word)) {
      current = sub;
      continue;
    }
    if (!subcommand_names(*current).empty() && current->get_require_subcommand_min() > 0) {
      const std::string what = current == &app ? "command" : current->get_name() + " command";
      return with_hint("unknown " + what + " '" + word + "'",
                       seqc::did_you_mean(word, subcommand_names(*current)));
    }
    positional_seen = true;
  }
  return std::nullopt;
}

const CLI::App* find_subcommand(const CLI::App& app, const std::vector<std::string>& names,
                                std::string& unknown) {
  const CLI::App* current = &app;
  for (const std::string& n : names) {
    const CLI::App* sub = child(*current, n);
    if (sub == nullptr) {
      unknown = with_hint("no help for '" + n + "': unknown command",
                          seqc::did_you_mean(n, subcommand_names(*current)));
      return nullptr;
    }
    current = sub;
  }
  return current;
}

}  // namespace seqc::cli
