#include "runtime/cli/docgen/command_model.hpp"

namespace seqc::cli::docgen {
namespace {

// CLI11 appends a validator's description to the type name: "TEXT:{auto,always,never}".
std::vector<std::string> choices_of(const std::string& type_name) {
  const auto open = type_name.find('{');
  const auto close = type_name.find('}', open);
  if (open == std::string::npos || close == std::string::npos) return {};
  std::vector<std::string> out;
  std::string word;
  for (char c : type_name.substr(open + 1, close - open - 1)) {
    if (c == ',') {
      out.push_back(word);
      word.clear();
    } else if (c != ' ') {
      word += c;
    }
  }
  if (!word.empty()) out.push_back(word);
  return out;
}

ValueKind kind_of(const OptionDoc& o) {
  if (o.value_name.empty()) return ValueKind::None;
  if (!o.choices.empty()) return ValueKind::Choice;
  for (const std::string& n : o.names) {
    if (n == "--port") return ValueKind::Port;
    if (n == "-o" || n == "--output" || n == "--trace" || n == "--record" || n == "--dump-groups") {
      return ValueKind::File;
    }
  }
  return ValueKind::Text;
}

}  // namespace

std::string CommandDoc::joined_path() const {
  std::string out;
  for (const std::string& p : path) out += (out.empty() ? "" : " ") + p;
  return out;
}

static CommandDoc describe_at(const CLI::App& app, std::vector<std::string> path) {
  CommandDoc doc;
  doc.path = path;
  doc.description = app.get_description();
  for (const CLI::Option* o : app.get_options()) {
    if (o->get_positional()) {
      PositionalDoc p;
      p.name = o->get_name();
      p.description = o->get_description();
      p.extension = p.description.find(".yaml") != std::string::npos ? "yaml yml" : "";
      p.repeats = o->get_items_expected_max() > 1;
      p.required = o->get_required();
      doc.positionals.push_back(p);
      continue;
    }
    OptionDoc d;
    for (const std::string& s : o->get_snames()) d.names.push_back("-" + s);
    for (const std::string& l : o->get_lnames()) d.names.push_back("--" + l);
    if (d.names.empty() || d.names.back() == "--help") continue;
    d.description = o->get_description();
    if (o->get_expected_max() > 0) {
      const std::string type = o->get_type_name();
      d.value_name = type.substr(0, type.find(':'));
      if (d.value_name.empty()) d.value_name = "VALUE";
      d.choices = choices_of(type);
    }
    d.kind = kind_of(d);
    doc.options.push_back(d);
  }
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; })) {
    std::vector<std::string> sub_path = path;
    sub_path.push_back(sub->get_name());
    doc.subcommands.push_back(describe_at(*sub, sub_path));
  }
  return doc;
}

CommandDoc describe(const CLI::App& app) { return describe_at(app, {}); }

}  // namespace seqc::cli::docgen
