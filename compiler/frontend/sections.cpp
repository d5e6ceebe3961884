// Sections (sections.hpp): a file's `sections`, and each performance with its parameters' values
// put in for every `$name`, and its expressions worked out, before its steps are walked.
#include "compiler/frontend/sections.hpp"

#include <algorithm>
#include <cctype>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "compiler/frontend/key_tables.hpp"
#include "compiler/frontend/param_expressions.hpp"

namespace seqc::compiler {
namespace {

// A section parameter's name: what may follow `$`.
bool parameter_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_'; }
bool is_parameter_name(std::string_view name) {
  return !name.empty() && std::isdigit(static_cast<unsigned char>(name[0])) == 0 &&
         std::all_of(name.begin(), name.end(), parameter_char);
}

bool mentions_parameter(const YamlNode& node) {
  if (node.scalar.find('$') != std::string::npos) return true;
  for (const YamlNode& item : node.items) {
    if (mentions_parameter(item)) return true;
  }
  for (const YamlEntry& e : node.entries) {
    if (mentions_parameter(e.first) || mentions_parameter(e.second)) return true;
  }
  return false;
}

// `in` with every `$name` and `${name}` replaced by the parameter's text; the names not in
// `values` go to `unknown`, located at `at`.
std::string splice_parameters(const std::string& in, Location at, const ParameterValues& values,
                              std::vector<std::pair<Location, std::string>>& unknown) {
  std::string out;
  for (std::size_t i = 0; i < in.size();) {
    const bool braced = in[i] == '$' && i + 1 < in.size() && in[i + 1] == '{';
    std::size_t from = i + (braced ? 2 : 1), to = from;
    while (in[i] == '$' && to < in.size() && parameter_char(in[to])) ++to;
    if (in[i] != '$' || to == from || (braced && (to >= in.size() || in[to] != '}'))) {
      out += in[i++];
      continue;
    }
    const std::string name = in.substr(from, to - from);
    auto it = values.find(name);
    if (it == values.end()) {
      unknown.emplace_back(at, name);
    } else {
      out += it->second;
    }
    i = to + (braced ? 1 : 0);
  }
  return out;
}

// Every `$name` and `${name}` in `node`'s keys and values replaced by the parameter's text, and
// every value that is an expression of parameters by what it comes to; the names not in
// `values` go to `unknown`, and what is wrong with an expression to `wrong`, with where they are
// written. A key is a name (`$joint`), never worked out.
void put_in_parameters(YamlNode& node, const ParameterValues& values, bool is_key,
                       std::vector<std::pair<Location, std::string>>& unknown,
                       std::vector<std::pair<Location, std::string>>& wrong) {
  if (node.scalar.find('$') != std::string::npos) {
    EvaluatedExpression e;
    if (!is_key) e = evaluate_parameter_expression(node.scalar, values);
    if (e.is_expression) {
      for (std::string& name : e.unknown) unknown.emplace_back(node.location, std::move(name));
      if (!e.error.empty()) wrong.emplace_back(node.location, std::move(e.error));
      node.scalar = std::move(e.value);
    } else {
      node.scalar = splice_parameters(node.scalar, node.location, values, unknown);
    }
  }
  for (YamlNode& item : node.items) put_in_parameters(item, values, false, unknown, wrong);
  for (YamlEntry& e : node.entries) {
    put_in_parameters(e.first, values, true, unknown, wrong);
    put_in_parameters(e.second, values, false, unknown, wrong);
  }
}

}  // namespace

void read_sections(const YamlNode& sections, FileScope& scope, Reporter& reporter) {
  if (!sections.is_map()) {
    reporter.error(sections.location, "'sections' must be a map of section names to step lists");
    return;
  }
  for (const auto& [name, list] : sections.entries) {
    scope.sections[name.scalar] = &list;
    scope.section_at[name.scalar] = name.location;
  }
}

const YamlNode* perform_section(const YamlNode& step, const YamlNode& name, const YamlNode& section,
                                YamlNode& copy, std::optional<Reporter::Note>& performance,
                                Reporter& reporter) {
  const std::string quoted = "section '" + name.scalar + "'";
  const Reporter::Note here{name.location, quoted + " is performed here"};
  const YamlNode* steps = &section;
  const YamlNode* params = nullptr;
  if (section.is_map()) {
    reporter.check_keys(section, kSectionKeys, "in a section");
    params = section.find("params");
    steps = section.find("steps");
    if (steps == nullptr) {
      reporter.error(section.location, quoted + " needs 'steps', the list of its steps");
      return nullptr;
    }
  }
  ParameterValues values;
  std::vector<std::string> names;  // in the order declared
  bool ok = true;
  if (params != nullptr && params->kind != YamlNode::Kind::Null) {
    if (!params->is_map()) {
      reporter.error(params->location,
                     "'params' must be a map of parameter names to default values, e.g. "
                     "'params: {amount: 40}'");
      return nullptr;
    }
    for (const auto& [key, v] : params->entries) {
      if (!is_parameter_name(key.scalar)) {
        reporter.error(key.location, "'" + key.scalar +
                                         "' cannot be a parameter name; use letters, digits "
                                         "and '_', starting with a letter");
        ok = false;
      } else if (!v.is_scalar()) {
        reporter.error(v.location, "parameter '" + key.scalar +
                                       "' needs a default that is a single value, e.g. '" +
                                       key.scalar + ": 40'");
        ok = false;
      } else {
        values[key.scalar] = v.scalar;
        names.push_back(key.scalar);
      }
    }
  }
  if (const YamlNode* with = step.find("with")) {
    if (!with->is_map()) {
      reporter.error(with->location,
                     "'with' gives the section's parameters values, e.g. 'with: {amount: 80}'",
                     here);
      return nullptr;
    }
    for (const auto& [key, v] : with->entries) {
      auto it = values.find(key.scalar);
      if (it == values.end()) {
        std::string message = quoted + " has no parameter '" + key.scalar + "'";
        const std::string suggestion = did_you_mean(key.scalar, names);
        if (!suggestion.empty()) {
          message += "; did you mean '" + suggestion + "'?";
        } else if (names.empty()) {
          message += "; it declares none (under 'params:')";
        }
        reporter.error(key.location, message, here);
        ok = false;
      } else if (!v.is_scalar()) {
        reporter.error(v.location,
                       "'" + key.scalar +
                           "' takes a single value, such as 80 or wrist_roll, "
                           "not " +
                           std::string(kind_name(v)),
                       here);
        ok = false;
      } else {
        it->second = v.scalar;
      }
    }
  }
  if (!ok) return nullptr;
  if (!values.empty()) {
    std::string given;
    for (const std::string& n : names) given += (given.empty() ? "" : ", ") + n + ": " + values[n];
    performance = Reporter::Note{name.location, quoted + " is performed here with " + given};
  }
  if (!mentions_parameter(*steps)) return steps;
  copy = *steps;
  std::vector<std::pair<Location, std::string>> unknown, wrong;
  put_in_parameters(copy, values, false, unknown, wrong);
  for (const auto& [at, word] : unknown) {
    std::string message = "unknown parameter '$" + word + "' in " + quoted;
    const std::string suggestion = did_you_mean(word, names);
    if (!suggestion.empty()) {
      message += "; did you mean '$" + suggestion + "'?";
    } else if (names.empty()) {
      message += ", which declares none; declare it under 'params:'";
    }
    reporter.error(at, message, performance.value_or(here));
  }
  for (const auto& [at, message] : wrong) reporter.error(at, message, performance.value_or(here));
  return unknown.empty() && wrong.empty() ? &copy : nullptr;
}

void run_section(const YamlNode& step, const YamlNode& value, const ScopeChain& scopes,
                 std::vector<const YamlNode*>& running, Reporter& reporter,
                 const std::function<void(const YamlNode& steps, const std::string& what)>& run) {
  const YamlNode* section = scopes.find_section(value, reporter);
  if (section == nullptr) return;
  if (std::find(running.begin(), running.end(), section) != running.end()) {
    reporter.error(value.location, "section '" + value.scalar + "' performs itself");
    return;
  }
  YamlNode copy;
  std::optional<Reporter::Note> performance;
  const YamlNode* list = perform_section(step, value, *section, copy, performance, reporter);
  if (list == nullptr) return;
  running.push_back(section);
  // A performance with values explains every mistake inside it; a plain one names itself
  // under the warnings (an error inside it is the section's own).
  if (performance) {
    reporter.push_context(*performance);
  } else {
    reporter.push_performance(value.location, value.scalar);
  }
  run(*list, "section '" + value.scalar + "'");
  if (performance) {
    reporter.pop_context();
  } else {
    reporter.pop_performance();
  }
  running.pop_back();
}

}  // namespace seqc::compiler
