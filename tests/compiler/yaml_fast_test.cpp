// The YAML loader's fast reader against yaml-cpp: whenever the fast reader accepts a text, its
// events (kind, mark, value) must be exactly yaml-cpp's, and yaml-cpp must accept the text too.
// Inputs: every YAML file in the repository, hand-picked edge cases, and a few hundred thousand
// generated texts (deterministic seeds) built from the subset's pieces plus characters that
// leave it.
#include <gtest/gtest.h>
#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/exceptions.h>
#include <yaml-cpp/mark.h>
#include <yaml-cpp/parser.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "compiler/yaml/yaml_fast.hpp"
#include "compiler/yaml/yaml_prescan.hpp"
#include "tests/compiler/yaml_events.hpp"

namespace seqc::compiler::yaml_detail {
namespace {

// Compares when the fast reader accepts; returns whether it did.
bool check(const std::string& text) {
  auto fast = fast_events(text, 64);
  if (!fast) return false;
  const YamlCppEvents cpp = yaml_cpp_events(text);
  const std::vector<Ev> got = from_fast(*fast);
  EXPECT_EQ(cpp.error, "") << "accepted by the fast reader:\n" << text;
  // The loader skips this pre-scan for accepted texts: it must have nothing to report.
  EXPECT_FALSE(check_flow_depth(text, 64).has_value()) << text;
  EXPECT_EQ(describe(got), describe(cpp.events)) << "text:\n" << text;
  return true;
}

TEST(YamlFast, RepositoryYamlFilesMatchYamlCpp) {
  std::size_t files = 0;
  std::size_t accepted = 0;
  for (const char* dir : {"examples", "tests/golden", "tests/compiler/hostile"}) {
    for (const auto& entry : std::filesystem::recursive_directory_iterator(
             std::filesystem::path(SEQC_SOURCE_DIR) / dir)) {
      if (entry.path().extension() != ".yaml") continue;
      std::ifstream in(entry.path(), std::ios::binary);
      std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
      if (text.size() > (1u << 20) || text.find('\0') != std::string::npos) continue;
      ++files;
      if (check(text)) ++accepted;
    }
  }
  EXPECT_GT(files, 20u);
  EXPECT_GT(accepted, files / 3) << "the fast reader should take most ordinary files";
  std::printf("fast reader took %zu of %zu repository YAML files\n", accepted, files);
}

TEST(YamlFast, EdgeCasesMatchYamlCpp) {
  const std::vector<std::string> accepted = {
      "a: 1",
      "a: 1\n",
      "a: 1\nb: two words\n",
      "a:   x   \nb: y # c\n# end",
      "# head\n\na: 1\n\n\n",
      "a:\n  b: 1\n  c:\n    d: 2\ne: 3\n",
      "a:\n- 1\n- 2\nb: 3\n",
      "a:\n  - 1\n  -   2\n",
      "- a\n- b\n",
      "- a: 1\n  b: 2\n- c: 3\n",
      "- - a\n  - b\n- c\n",
      "-   x: 1\n    y: [1, 2]\n",
      "- a:\n  - x\n  - y\n- b\n",
      "- a:\n    b: 1\n",
      "-\n  a: 1\n",
      "- # c\n  a: 1\n",
      "a: # c\n  b: 1\n",
      "a: {}\nb: []\n",
      "a: {x: 1, y: [2, 3], z: {w: -4}}\n",
      "a: [ 1 ,2 , 3 ]\n",
      "a: {x y: p q}\n",
      "a: null\nNull: b\nc: NULL\n",
      "a: nulls\n",
      "a: -5\nb: +3deg\nc: .5\nd: x/y.z\ne: a - b\nf: a -b\n",
      "move: {ch0: 600, ch1: 653}\ntime: 20ms\n",
      "a:\n  {x: 1}\n",
      "a:\n  scalar\nb: 1\n",
      "[a, b]\n",
      "{a: 1}\n",
      "a: 1\na: 2\n",
      "a: " + std::string(2000, 'x') + "\n",
      std::string(1000, 'k') + ": v\n",
      "a: {" + std::string(1000, 'k') + ": v}\n",
      "- " + std::string(1000, 'k') + ": v\n",
      "a: 1 # caf\xC3\xA9\nb: 2\n",
      "# \xE2\x82\xAC\nb: 2\n",
  };
  for (const std::string& text : accepted) {
    EXPECT_TRUE(check(text)) << "expected the fast reader to take:\n" << text;
  }
  const std::vector<std::string> refused = {
      "",
      "# only a comment\n",
      "a:\n",
      "a:\nb: 1\n",
      "a: 'q'\n",
      "a: \"q\"\n",
      "a: ~\n",
      "a: !!str 1\n",
      "a: &x 1\n",
      "a: *x\n",
      "a: |\n  text\n",
      "a: b\n  c\n",
      "a: b\n# c\n  c\n",
      "a: 1\n- b\n",
      "a:b\n",
      "a : b\n",
      "a: b: c\n",
      "a: b#c\n",
      "a:\t1\n",
      "a: 1\r\nb: 2\r\n",
      "---\na: 1\n",
      "a: 1\n...\n",
      "a: 1\n---\nb: 2\n",
      "  a: 1\n",
      "a: {x: 1,}\n",
      "a: {x:1}\n",
      "a: [x: 1]\n",
      "a: {x: 1\n  }\n",
      "a: [1,\n 2]\n",
      "a: {x: 1}}\n",
      "a: {x: 1} b\n",
      "{a: 1}: b\n",
      "? a\n: b\n",
      "a: 1\n ,\n",
      "a: -\n",
      "a: - b\n",
      "- a\n  b\n",
      "a:\n  b: 1\n c: 2\n",
      "a: b,c\n",
      "a: x%y\n",
      std::string(1001, 'k') + ": v\n",
      "a: {" + std::string(1001, 'k') + ": v}\n",
      "- " + std::string(1001, 'k') + ": v\n",
  };
  for (const std::string& text : refused) {
    EXPECT_FALSE(fast_events(text, 64).has_value()) << "expected a fallback for:\n" << text;
  }
}

TEST(YamlFast, DepthLimitFallsBack) {
  std::string deep;
  for (int i = 0; i < 64; ++i) deep += std::string(static_cast<std::size_t>(i), ' ') + "k:\n";
  deep += std::string(64, ' ') + "k: v\n";
  EXPECT_FALSE(fast_events(deep, 64).has_value());  // 65 maps
  EXPECT_TRUE(fast_events(deep, 65).has_value());
  EXPECT_FALSE(fast_events(std::string(100000, '[') + std::string(100000, ']'), 64).has_value());
}

// Random texts over the characters that matter to the subset's edges.
TEST(YamlFast, RandomShortTextsMatchYamlCpp) {
  const std::string alphabet = "ab1 -:#{}[],\n.+_/";
  std::mt19937 rng(20240601);
  std::size_t accepted = 0;
  for (int n = 0; n < 200000; ++n) {
    const std::size_t len = 1 + rng() % 14;
    std::string text;
    for (std::size_t i = 0; i < len; ++i) text += alphabet[rng() % alphabet.size()];
    if (check(text)) ++accepted;
    if (HasFailure()) return;
  }
  EXPECT_GT(accepted, 1000u);
  std::printf("fast reader took %zu of 200000 random texts\n", accepted);
}

// Random documents assembled from lines of the subset, with the occasional line broken.
TEST(YamlFast, RandomDocumentsMatchYamlCpp) {
  const std::vector<std::string> pieces = {
      "k: v",  "k: 1 2", "k:",   "- x",      "- k: v", "-",       "- - x", "k: {a: 1, b: [x, y]}",
      "k: []", "[a, b]", "# c",  "",         "k: -1",  "k: null", "- {}",  "k: v # c",
      "k2: w", "- k:",   "a b:", "k: {a: 1", "k: ]",   "k: v:",   "- -",   "k: 'q'",
  };
  std::mt19937 rng(7);
  std::size_t accepted = 0;
  for (int n = 0; n < 100000; ++n) {
    std::string text;
    const std::size_t lines = 1 + rng() % 6;
    for (std::size_t l = 0; l < lines; ++l) {
      text += std::string(rng() % 3 == 0 ? 0 : 2 * (rng() % 3), ' ');
      text += pieces[rng() % pieces.size()];
      if (l + 1 < lines || rng() % 2) text += '\n';
    }
    if (check(text)) ++accepted;
    if (HasFailure()) return;
  }
  EXPECT_GT(accepted, 5000u);
  std::printf("fast reader took %zu of 100000 random documents\n", accepted);
}

}  // namespace
}  // namespace seqc::compiler::yaml_detail
