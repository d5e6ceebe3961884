// textDocument/definition, references, prepareRename and rename: poses, sections, parameters
// and groups by name across the file and the files it includes (a parameter within its
// section: its key in `params`, every `$name` and `${name}` in the section's steps and the
// `with:` keys of its performances), and an `include:` path, whose definition is the file.
#include <map>
#include <string>
#include <vector>

#include "runtime/lsp/feature_parts.hpp"

namespace seqc::lsp {

using nlohmann::json;

namespace {

const Name* name_at_request(const Request& r) {
  if (!r.position) return nullptr;
  return r.analysis->name_at(*r.file, *r.position);
}

bool renamable(const Name& n) {
  return n.kind == NameKind::Pose || n.kind == NameKind::Section || n.kind == NameKind::Param ||
         n.kind == NameKind::Group;
}

// Letters, digits and '_', not starting with a digit: what the language takes for a name.
bool valid_name(const std::string& s) {
  if (s.empty() || (s[0] >= '0' && s[0] <= '9')) return false;
  for (char c : s) {
    const bool ok =
        (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
    if (!ok) return false;
  }
  return true;
}

}  // namespace

json definition(Request& r) {
  const Name* n = name_at_request(r);
  if (n == nullptr) return nullptr;
  if (n->kind == NameKind::Include) {
    const json start = position_json({});
    return {{"uri", r.ctx.path_to_uri(n->target)}, {"range", {{"start", start}, {"end", start}}}};
  }
  const Name* def = r.analysis->definition_of(*n);
  if (def == nullptr) return nullptr;
  return location_json(r, def->span);
}

json references(Request& r) {
  json out = json::array();
  const Name* n = name_at_request(r);
  if (n == nullptr || n->kind == NameKind::Step) return out;
  bool declarations = true;
  if (const auto context = r.params.find("context");
      context != r.params.end() && context->is_object()) {
    declarations = context->value("includeDeclaration", true);
  }
  for (const Name* m : r.analysis->same(*n)) {
    if (m->definition && !declarations) continue;
    out.push_back(location_json(r, m->span));
  }
  return out;
}

json prepare_rename(Request& r) {
  const Name* n = name_at_request(r);
  if (n == nullptr || !renamable(*n)) return nullptr;
  return {{"range", range_json(*r.analysis, n->span)}, {"placeholder", n->text}};
}

json rename(Request& r) {
  const Name* n = name_at_request(r);
  if (n == nullptr || !renamable(*n)) return nullptr;
  const json& new_name = r.params.value("newName", json());
  if (!new_name.is_string() || !valid_name(new_name.get<std::string>())) return nullptr;
  std::map<std::string, json> changes;
  for (const Name* m : r.analysis->same(*n)) {
    json& edits = changes[uri_of(r, m->span.file)];
    if (edits.is_null()) edits = json::array();
    edits.push_back({{"range", range_json(*r.analysis, m->span)}, {"newText", new_name}});
  }
  json out = {{"changes", json::object()}};
  for (auto& [uri, edits] : changes) out["changes"][uri] = std::move(edits);
  return out;
}

}  // namespace seqc::lsp
