// The loader on anchors, aliases and merge keys: copies that keep the anchor's locations, YAML
// 1.1 merge order, and the located errors for undefined aliases, cycles and alias bombs.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <string>

#include "base/diagnostics.hpp"
#include "compiler/frontend/yaml/yaml_tree.hpp"

namespace seqc::compiler {
namespace {

class YamlAnchorsTest : public ::testing::Test {
 protected:
  std::optional<YamlNode> load(std::string text, const YamlLimits& limits = {}) {
    file_ = sources_.add("t.yaml", std::move(text));
    return load_yaml(sources_, file_, diags_, limits);
  }
  std::string rendered() const { return render_all(diags_, sources_); }
  Location at(std::uint32_t line, std::uint32_t column) const { return {file_, line, column}; }

  SourceManager sources_;
  Diagnostics diags_;
  std::uint32_t file_ = 0;
};

// The keys of a map, in order, as "k=v" for scalar values.
std::string keys_of(const YamlNode& map) {
  std::string out;
  for (const auto& [k, v] : map.entries) {
    if (!out.empty()) out += ' ';
    out += k.scalar + "=" + (v.is_scalar() ? v.scalar : "?");
  }
  return out;
}

TEST_F(YamlAnchorsTest, AnAliasIsACopyAtTheAnchorsLocationUsedAtTheAlias) {
  const auto root = load("a: &p {x: 1, y: [2, 3]}\nb: *p\n");
  ASSERT_TRUE(root) << rendered();
  EXPECT_EQ(rendered(), "");
  const YamlNode* a = root->find("a");
  const YamlNode* b = root->find("b");
  ASSERT_NE(b, nullptr);
  ASSERT_TRUE(b->is_map());
  EXPECT_EQ(keys_of(*b), "x=1 y=?");
  ASSERT_EQ(b->find("y")->items.size(), 2u);
  EXPECT_EQ(b->find("y")->items[1].scalar, "3");
  // The copy is located at the anchored node ('&' at 1:4), and remembers the alias (2:4).
  EXPECT_EQ(b->location, at(1, 4));
  EXPECT_EQ(b->used_at, at(2, 4));
  EXPECT_EQ(b->entries[0].first.location, at(1, 8));
  EXPECT_EQ(b->entries[0].first.used_at, at(2, 4));
  EXPECT_EQ(b->find("y")->items[1].used_at, at(2, 4));
  // The written node is not a copy.
  EXPECT_EQ(a->location, at(1, 4));
  EXPECT_EQ(a->used_at.line, 0u);

  AliasUses uses;
  uses.add(*root);
  EXPECT_EQ(uses.sites(at(1, 8)), std::vector<Location>{at(2, 4)});
  EXPECT_TRUE(uses.sites(at(2, 1)).empty());
}

TEST_F(YamlAnchorsTest, ScalarAnchorsAndARedefinedAnchor) {
  // YAML lets a later anchor take the name; an alias copies the latest before it.
  const auto root = load("a: &x 1\nb: *x\nc: &x 2\nd: *x\n");
  ASSERT_TRUE(root) << rendered();
  EXPECT_EQ(keys_of(*root), "a=1 b=1 c=2 d=2");
  EXPECT_EQ(root->find("d")->location, at(3, 4));
}

TEST_F(YamlAnchorsTest, MergeKeyKeysWrittenInTheMapWin) {
  const auto root = load("base: &base {x: 1, y: 2}\nstep:\n  <<: *base\n  y: 5\n");
  ASSERT_TRUE(root) << rendered();
  EXPECT_EQ(rendered(), "");
  // Merged entries go where the '<<' was; 'y' is the map's own, though written after it.
  EXPECT_EQ(keys_of(*root->find("step")), "x=1 y=5");
  EXPECT_EQ(root->find("step")->find("y")->location, at(4, 6));
}

TEST_F(YamlAnchorsTest, AListOfMergesEarlierMapsWin) {
  const auto root = load(
      "a: &a {x: 1, y: 1}\n"
      "b: &b {y: 2, z: 2}\n"
      "c:\n"
      "  w: 0\n"
      "  <<: [*a, *b]\n"
      "  v: 9\n");
  ASSERT_TRUE(root) << rendered();
  EXPECT_EQ(rendered(), "");
  EXPECT_EQ(keys_of(*root->find("c")), "w=0 x=1 y=1 z=2 v=9");
}

TEST_F(YamlAnchorsTest, AQuotedMergeKeyIsAPlainKey) {
  const auto root = load("a: &a {x: 1}\nb: {'<<': *a}\n");
  ASSERT_TRUE(root) << rendered();
  ASSERT_EQ(root->find("b")->entries.size(), 1u);
  EXPECT_EQ(root->find("b")->entries[0].first.scalar, "<<");
}

TEST_F(YamlAnchorsTest, MisusedMergeKeysAreErrorsAndTheRestIsRead) {
  const auto root = load(
      "a: {<<: 5, x: 1}\n"
      "b: {<<: [{y: 1}, 7]}\n"
      "c: {<<: {z: 1}, <<: {z: 2}}\n"
      "d: [1, 2\n"
      "]\n");
  EXPECT_TRUE(root);
  EXPECT_EQ(rendered(),
            "t.yaml:1:9: error: the merge key '<<' takes a map or a list of maps, not a single "
            "value\n"
            "    1 | a: {<<: 5, x: 1}\n"
            "      |         ^\n"
            "t.yaml:2:18: error: the merge key '<<' takes a list of maps; this item is a single "
            "value\n"
            "    2 | b: {<<: [{y: 1}, 7]}\n"
            "      |                  ^\n"
            "t.yaml:3:17: error: duplicate key '<<'\n"
            "    3 | c: {<<: {z: 1}, <<: {z: 2}}\n"
            "      |                 ^\n"
            "t.yaml:3:5: note: first defined here\n"
            "    3 | c: {<<: {z: 1}, <<: {z: 2}}\n"
            "      |     ^\n");
  EXPECT_EQ(keys_of(*root->find("a")), "x=1");
  EXPECT_EQ(keys_of(*root->find("b")), "y=1");
  EXPECT_EQ(keys_of(*root->find("c")), "z=1");
}

TEST_F(YamlAnchorsTest, UndefinedAliasNamesTheAnchor) {
  EXPECT_FALSE(load("a: *nothing\nb: &nothing 1\n"));
  EXPECT_EQ(rendered(),
            "t.yaml:1:4: error: undefined alias '*nothing' (no anchor '&nothing' before it)\n"
            "    1 | a: *nothing\n"
            "      |    ^\n");
}

TEST_F(YamlAnchorsTest, AnAliasInsideItsOwnAnchoredNodeIsACycle) {
  // yaml-cpp defines the anchor before reading its node, so this alias does find it.
  EXPECT_FALSE(load("poses: &p\n  a: *p\n"));
  EXPECT_EQ(rendered(),
            "t.yaml:2:6: error: alias '*p' is inside the node it refers to (a node cannot "
            "contain itself)\n"
            "    2 |   a: *p\n"
            "      |      ^\n"
            "t.yaml:1:8: note: anchor '&p' is here\n"
            "    1 | poses: &p\n"
            "      |        ^\n");
}

TEST_F(YamlAnchorsTest, BillionLaughsIsRefusedAtTheAliasThatPassesTheBudget) {
  // Nine levels of ten aliases each: 3 * 10^9 nodes if expanded. l0 is 3 nodes (map, key,
  // value), l1 31, l2 311, l3 3,111, l4 31,111: 34,560 copied by the end of line 5. Each alias
  // on line 6 copies 31,111 more: seven fit in 262,144 (252,337), the eighth, at column
  // 10 + 7 * 5 = 45, does not.
  std::string text = "l0: &l0 {base: 1}\n";
  for (int i = 1; i <= 9; ++i) {
    const std::string prev = "*l" + std::to_string(i - 1);
    text += "l" + std::to_string(i) + ": &l" + std::to_string(i) + " [" + prev;
    for (int k = 1; k < 10; ++k) text += ", " + prev;
    text += "]\n";
  }
  const auto start = std::chrono::steady_clock::now();
  EXPECT_FALSE(load(text));
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  const std::string expected =
      "t.yaml:6:45: error: aliases expand to more than 262144 nodes (a YAML \"billion "
      "laughs\"?)\n";
  EXPECT_EQ(rendered().substr(0, expected.size()), expected);
  EXPECT_EQ(diags_.all().size(), 1u);
  EXPECT_LT(ms, 2000.0);  // milliseconds in fact; generous for a loaded machine
  std::printf("[ measured ] 9 levels of 10 aliases refused in %.3f ms\n", ms);
}

TEST_F(YamlAnchorsTest, TheBudgetIsCheckedBeforeTheCopy) {
  YamlLimits limits;
  limits.max_alias_nodes = 6;
  // Each alias copies 3 nodes: two fit exactly, the third does not.
  EXPECT_FALSE(load("a: &a {x: 1}\nb: [*a, *a, *a]\n", limits));
  EXPECT_EQ(rendered().substr(0, rendered().find('\n')),
            "t.yaml:2:13: error: aliases expand to more than 6 nodes (a YAML \"billion laughs\"?)");
}

TEST_F(YamlAnchorsTest, ACopyMayNotNestPastTheDepthLimit) {
  YamlLimits limits;
  limits.max_depth = 3;
  // 'a' nests two deep and fits at the top; under 'b: {c: ...}' it would be four deep.
  EXPECT_FALSE(load("a: &a [[x]]\nb: {c: *a}\n", limits));
  EXPECT_EQ(rendered().substr(0, rendered().find('\n')),
            "t.yaml:2:8: error: nesting is deeper than 3 levels");
}

}  // namespace
}  // namespace seqc::compiler
