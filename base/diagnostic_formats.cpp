#include "base/diagnostic_formats.hpp"

#include <cctype>
#include <cstdio>
#include <string_view>

#include "base/diagnostic_rules.hpp"
#include "base/json_text.hpp"

namespace seqc {
namespace {

// One diagnostic with the notes that follow it, located.
struct Place {
  std::string file;
  std::uint32_t line = 0;  // 0: the file as a whole
  std::uint32_t column = 0;
};

struct Entry {
  const Diagnostic* main = nullptr;  // nullptr for a file that could not be read
  std::string read_error;
  Place at;
  std::vector<std::pair<Place, std::string>> notes;
};

Place place_of(const Location& l, const CheckedFile& f) {
  const SourceManager& sources = *f.sources;
  if (l.file >= sources.file_count()) return {f.path, 0, 0};  // no file: the one checked
  Place p{sources.path(l.file), l.line, l.column};
  if (p.line > 0 && p.column == 0) p.column = 1;
  return p;
}

std::vector<Entry> entries(const std::vector<CheckedFile>& files) {
  std::vector<Entry> out;
  for (const CheckedFile& f : files) {
    if (f.read_error) {
      out.push_back({nullptr, *f.read_error, {f.path, 0, 0}, {}});
      continue;
    }
    for (const Diagnostic& d : f.diagnostics->all()) {
      if (d.severity == Severity::Note && !out.empty() && out.back().main != nullptr) {
        out.back().notes.emplace_back(place_of(d.location, f), d.message);
      } else if (d.severity != Severity::Note) {
        out.push_back({&d, "", place_of(d.location, f), {}});
      }
    }
  }
  return out;
}

std::string severity(const Entry& e, bool strict) {
  if (e.main == nullptr || e.main->severity == Severity::Error) return "error";
  return strict ? "error" : "warning";
}

std::string rule_id(const Entry& e) {
  return e.main == nullptr ? "file-error" : std::string(rule_for(*e.main).id);
}

std::string message(const Entry& e) { return e.main == nullptr ? e.read_error : e.main->message; }

std::string json_place(const Place& p) {
  std::string out = "\"file\": " + json_string(p.file);
  if (p.line > 0) {
    out += ", \"line\": " + std::to_string(p.line) + ", \"column\": " + std::to_string(p.column);
  }
  return out;
}

// A URI reference for a path: unreserved characters and '/' as they are, the rest
// percent-encoded; absolute paths become file:// URIs.
std::string uri_of(const std::string& path) {
  std::string out = path.starts_with("/") ? "file://" : "";
  for (unsigned char c : path) {
    if (std::isalnum(c) || c == '-' || c == '.' || c == '_' || c == '~' || c == '/') {
      out += static_cast<char>(c);
    } else {
      char buf[4];
      std::snprintf(buf, sizeof buf, "%%%02X", c);
      out += buf;
    }
  }
  return out;
}

std::string sarif_location(const Place& p) {
  std::string out = "{\"artifactLocation\": {\"uri\": " + json_string(uri_of(p.file)) + "}";
  if (p.line > 0) {
    out += ", \"region\": {\"startLine\": " + std::to_string(p.line) +
           ", \"startColumn\": " + std::to_string(p.column) + "}";
  }
  return out + "}";
}

// SARIF asks for a rule's name in upper camel case: "Unknown key" -> "UnknownKey".
std::string camel(std::string_view title) {
  std::string out;
  bool up = true;
  for (char c : title) {
    if (c == ' ' || c == '-') {
      up = true;
    } else {
      out += up ? static_cast<char>(std::toupper(static_cast<unsigned char>(c))) : c;
      up = false;
    }
  }
  return out;
}

}  // namespace

std::string diagnostics_json(const std::vector<CheckedFile>& files, bool strict) {
  std::string out = "[";
  bool first = true;
  for (const Entry& e : entries(files)) {
    out += first ? "\n  {" : ",\n  {";
    first = false;
    out += json_place(e.at) + ", \"severity\": \"" + severity(e, strict) + "\", \"rule\": \"" +
           rule_id(e) + "\", \"message\": " + json_string(message(e)) + ", \"notes\": [";
    for (std::size_t i = 0; i < e.notes.size(); ++i) {
      out += (i ? ", {" : "{") + json_place(e.notes[i].first) +
             ", \"message\": " + json_string(e.notes[i].second) + "}";
    }
    out += "]}";
  }
  return out + (first ? "]\n" : "\n]\n");
}

std::string diagnostics_sarif(const std::vector<CheckedFile>& files, bool strict,
                              const std::string& version) {
  const auto& rules = diagnostic_rules();
  std::string out =
      "{\n  \"$schema\": \"https://json.schemastore.org/sarif-2.1.0.json\",\n"
      "  \"version\": \"2.1.0\",\n  \"runs\": [{\n    \"tool\": {\"driver\": {\"name\": \"seqc\", "
      "\"version\": " +
      json_string(version) + ", \"rules\": [";
  for (std::size_t i = 0; i <= rules.size(); ++i) {
    const bool file_rule = i == rules.size();
    const std::string id = file_rule ? "file-error" : std::string(rules[i].id);
    const std::string title = file_rule ? "File error" : std::string(rules[i].title);
    const std::string help = file_rule ? "A file could not be read." : std::string(rules[i].help);
    out += (i ? ",\n      " : "\n      ") + std::string("{\"id\": ") + json_string(id) +
           ", \"name\": " + json_string(camel(title)) +
           ", \"shortDescription\": {\"text\": " + json_string(help) + "}}";
  }
  out += "]}},\n    \"results\": [";
  bool first = true;
  for (const Entry& e : entries(files)) {
    const std::string id = rule_id(e);
    std::size_t index = rules.size();
    for (std::size_t i = 0; i < rules.size(); ++i) {
      if (rules[i].id == id) index = i;
    }
    out += first ? "\n      {" : ",\n      {";
    first = false;
    out += "\"ruleId\": " + json_string(id) + ", \"ruleIndex\": " + std::to_string(index) +
           ", \"level\": \"" + severity(e, strict) +
           "\", \"message\": {\"text\": " + json_string(message(e)) +
           "}, \"locations\": [{\"physicalLocation\": " + sarif_location(e.at) + "}]";
    if (!e.notes.empty()) {
      out += ", \"relatedLocations\": [";
      for (std::size_t i = 0; i < e.notes.size(); ++i) {
        out += (i ? ", {\"id\": " : "{\"id\": ") + std::to_string(i + 1) +
               ", \"physicalLocation\": " + sarif_location(e.notes[i].first) +
               ", \"message\": {\"text\": " + json_string(e.notes[i].second) + "}}";
      }
      out += "]";
    }
    out += "}";
  }
  out += first ? "]\n  }]\n}\n" : "\n    ]\n  }]\n}\n";
  return out;
}

}  // namespace seqc
