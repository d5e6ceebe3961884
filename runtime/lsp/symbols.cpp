// textDocument/documentSymbol: the file's outline: its poses, groups and sections (a section's
// parameters inside it), each at the name that defines it.
#include <map>
#include <string>
#include <vector>

#include "runtime/lsp/feature_parts.hpp"

namespace seqc::lsp {

using nlohmann::json;

namespace {

// SymbolKind values of the protocol.
enum SymbolKind : int { kFunction = 12, kVariable = 13, kConstant = 14, kArray = 18 };

json symbol(const Analysis& a, const Name& n, int kind, const char* detail) {
  const json range = range_json(a, n.span);
  return {{"name", n.text}, {"detail", detail},        {"kind", kind},
          {"range", range}, {"selectionRange", range}, {"children", json::array()}};
}

}  // namespace

json document_symbols(Request& r) {
  json out = json::array();
  const Analysis& a = *r.analysis;
  // Each section's parameters, gathered once (a file may hold thousands of sections).
  std::map<std::string, std::vector<const Name*>> params;
  for (const Name& p : a.names()) {
    if (p.kind == NameKind::Param && p.definition && p.span.file == *r.file) {
      params[p.section].push_back(&p);
    }
  }
  for (const Name& n : a.names()) {
    if (!n.definition || n.span.file != *r.file) continue;
    if (n.kind == NameKind::Pose) {
      out.push_back(symbol(a, n, kConstant, "pose"));
    } else if (n.kind == NameKind::Group) {
      out.push_back(symbol(a, n, kArray, "group"));
    } else if (n.kind == NameKind::Section) {
      json section = symbol(a, n, kFunction, "section");
      if (auto it = params.find(n.text); it != params.end()) {
        for (const Name* p : it->second) {
          section["children"].push_back(symbol(a, *p, kVariable, "parameter"));
        }
        params.erase(it);  // a section defined twice lists its parameters once
      }
      out.push_back(std::move(section));
    }
  }
  return out;
}

}  // namespace seqc::lsp
