// yaml-suite-check DIR: the YAML test suite's cases (written into DIR by scripts/yaml-suite.sh:
// ID.yaml, ID.tree with the expected events, ID.fail when the YAML is invalid) through yaml-cpp
// and through seqc's guarded loader (load_yaml, which reads with yaml-cpp and adds its own
// checks). Per case: whether yaml-cpp agrees with the suite, and what seqc does with the case
// (loads it, or rejects it with a located error). Prints one line per case, then the cases where
// yaml-cpp is wrong grouped by what seqc does about them, then the counts.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/exceptions.h>
#include <yaml-cpp/mark.h>
#include <yaml-cpp/parser.h>

#include "base/diagnostics.hpp"
#include "compiler/frontend/yaml/yaml_tree.hpp"

namespace fs = std::filesystem;

namespace {

std::string read(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The suite's escaping of scalar values in its event trees.
std::string escape(const std::string& v) {
  std::string out;
  for (char c : v) {
    switch (c) {
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\t':
        out += "\\t";
        break;
      case '\r':
        out += "\\r";
        break;
      case '\b':
        out += "\\b";
        break;
      default:
        out += c;
    }
  }
  return out;
}

// yaml-cpp's events of every document as the suite writes them, without styles, anchors and
// tags (yaml-cpp's event API does not report styles; anchors and tags are compared by neither).
class SuiteRecorder final : public YAML::EventHandler {
 public:
  std::vector<std::string> lines;
  void OnDocumentStart(const YAML::Mark&) override {}
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark&, YAML::anchor_t) override { lines.push_back("=VAL "); }
  void OnAlias(const YAML::Mark&, YAML::anchor_t) override { lines.push_back("=ALI"); }
  void OnAnchor(const YAML::Mark&, const std::string&) override {}
  void OnScalar(const YAML::Mark&, const std::string&, YAML::anchor_t,
                const std::string& value) override {
    lines.push_back("=VAL " + escape(value));
  }
  void OnSequenceStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                       YAML::EmitterStyle::value) override {
    lines.push_back("+SEQ");
  }
  void OnSequenceEnd() override { lines.push_back("-SEQ"); }
  void OnMapStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                  YAML::EmitterStyle::value) override {
    lines.push_back("+MAP");
  }
  void OnMapEnd() override { lines.push_back("-MAP"); }
};

// The suite's tree in the same terms.
std::vector<std::string> expected(const std::string& tree) {
  std::vector<std::string> out;
  std::istringstream in(tree);
  for (std::string line; std::getline(in, line);) {
    line.erase(0, line.find_first_not_of(' '));
    const std::string head = line.substr(0, 4);
    if (head == "+STR" || head == "-STR" || head == "+DOC" || head == "-DOC" || line.empty()) {
      continue;
    }
    if (head == "+SEQ" || head == "-SEQ" || head == "+MAP" || head == "-MAP") {
      out.push_back(head);
    } else if (head == "=ALI") {
      out.push_back("=ALI");
    } else if (head == "=VAL") {
      std::string rest = line.substr(5);
      while (!rest.empty() && (rest[0] == '&' || rest[0] == '<')) {  // anchor, tag
        const auto space = rest.find(' ');
        rest = space == std::string::npos ? "" : rest.substr(space + 1);
      }
      out.push_back("=VAL " + (rest.empty() ? "" : rest.substr(1)));  // drop the style
    }
  }
  return out;
}

// What seqc's loader does with `text`: "loads", or "rejects: <first error line>".
std::string seqc_outcome(const std::string& text) {
  seqc::SourceManager sources;
  seqc::Diagnostics diags;
  const auto file = sources.add("case.yaml", text);
  const auto root = seqc::compiler::load_yaml(sources, file, diags);
  if (root && !diags.has_errors()) return "loads";
  const std::string all = seqc::render_all(diags, sources);
  return "rejects: " + all.substr(0, all.find('\n'));
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: yaml-suite-check DIR\n");
    return 2;
  }
  std::vector<fs::path> cases;
  for (const auto& e : fs::directory_iterator(argv[1])) {
    if (e.path().extension() == ".yaml") cases.push_back(e.path());
  }
  std::sort(cases.begin(), cases.end());
  std::map<std::string, int> counts;
  std::map<std::string, std::vector<std::string>> wrong;  // "yaml-cpp X, seqc Y" -> case ids
  for (const fs::path& yaml : cases) {
    const std::string id = yaml.stem().string();
    const std::string text = read(yaml);
    const bool invalid = fs::exists(fs::path(yaml).replace_extension(".fail"));
    SuiteRecorder all;
    bool cpp_error = false;
    try {
      std::istringstream in(text);
      YAML::Parser parser(in);
      while (parser.HandleNextDocument(all)) {
      }
    } catch (const YAML::Exception&) {
      cpp_error = true;
    }
    std::string cpp;
    if (invalid) {
      cpp = cpp_error ? "rejects-invalid" : "ACCEPTS-INVALID";
    } else if (cpp_error) {
      cpp = "REJECTS-VALID";
    } else {
      cpp = all.lines == expected(read(fs::path(yaml).replace_extension(".tree"))) ? "agrees"
                                                                                   : "WRONG-TREE";
    }
    const std::string seqc = seqc_outcome(text);
    const bool loads = seqc == "loads";
    ++counts["yaml-cpp " + cpp];
    ++counts[std::string("seqc ") + (loads ? "loads" : "rejects") +
             (invalid ? " (invalid case)" : " (valid case)")];
    if (cpp != "agrees" && cpp != "rejects-invalid") {
      wrong[cpp + ", seqc " + (loads ? "loads it" : "rejects it")].push_back(id);
    }
    std::printf("%s yaml-cpp=%s seqc=%s\n", id.c_str(), cpp.c_str(), seqc.c_str());
  }
  std::printf("\nwhere yaml-cpp is wrong, and what seqc does:\n");
  for (const auto& [what, ids] : wrong) {
    std::printf("  %s (%zu):", what.c_str(), ids.size());
    for (const auto& id : ids) std::printf(" %s", id.c_str());
    std::printf("\n");
  }
  std::printf("%zu cases:", cases.size());
  for (const auto& [what, n] : counts) std::printf(" %s %d;", what.c_str(), n);
  std::printf("\n");
  return 0;
}
