// yaml_worst_bench: how long the guarded YAML loader takes on the largest inputs of the shapes
// that are slowest for a YAML parser (1 MiB each: long flow lists and maps, a long block list,
// and runs of '[' and ','). For each: steady_clock around load_yaml() alone (the text is already
// in memory), the outcome (loaded, or the first diagnostic line), best of --runs (default 3).
//
// Usage: yaml_worst_bench [--runs N]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "base/diagnostics.hpp"
#include "compiler/frontend/yaml/yaml_tree.hpp"

namespace {

using namespace seqc;
using namespace seqc::compiler;

struct Outcome {
  double ms = 0;
  std::string what;
};

Outcome load_once(const std::string& text) {
  SourceManager sources;
  Diagnostics diags;
  const auto file = sources.add("worst.yaml", text);
  const auto start = std::chrono::steady_clock::now();
  const auto root = load_yaml(sources, file, diags);
  const auto end = std::chrono::steady_clock::now();
  Outcome o;
  o.ms = std::chrono::duration<double, std::milli>(end - start).count();
  if (root) {
    o.what = "loaded";
  } else {
    const std::string all = render_all(diags, sources);
    o.what = all.substr(0, all.find('\n'));
  }
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  int runs = 3;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--runs" && i + 1 < argc) {
      runs = std::max(1, std::atoi(argv[++i]));
    } else {
      std::fprintf(stderr, "usage: yaml_worst_bench [--runs N]\n");
      return 2;
    }
  }
  std::string flow_list = "[";
  while (flow_list.size() < (1u << 20) - 8) flow_list += "a, ";
  flow_list += "a]";
  const std::string flow_unclosed = flow_list.substr(0, flow_list.size() - 1);
  std::string flow_map = "{";
  for (int i = 0; flow_map.size() < (1u << 20) - 32; ++i) {
    flow_map += "k" + std::to_string(i) + ": v, ";
  }
  flow_map += "z: v}";
  std::string block_seq;
  while (block_seq.size() < (1u << 20) - 8) block_seq += "- v\n";
  struct Case {
    const char* what;
    std::string text;
  };
  const Case cases[] = {
      {"1 MiB flow list of 'a, ' (valid)", flow_list},
      {"1 MiB flow list, unclosed", flow_unclosed},
      {"1 MiB flow map (valid)", flow_map},
      {"1 MiB block list (valid)", block_seq},
      {"1 MiB of '['", std::string((1u << 20) - 1, '[')},
      {"1 MiB of ','", std::string((1u << 20) - 1, ',')},
  };
  std::printf("yaml_worst_bench: load_yaml() on text in memory, steady_clock, best of %d\n", runs);
  for (const Case& c : cases) {
    Outcome best;
    for (int r = 0; r < runs; ++r) {
      Outcome o = load_once(c.text);
      if (r == 0 || o.ms < best.ms) best = o;
    }
    std::printf("%-34s %8zu bytes: %8.1f ms, %s\n", c.what, c.text.size(), best.ms,
                best.what.c_str());
  }
  return 0;
}
