// The loader on well-formed YAML: tree shape, scalars, quoting, nulls and 1-based locations.
#include <gtest/gtest.h>

#include <string>

#include "base/diagnostics.hpp"
#include "compiler/frontend/yaml/yaml_tree.hpp"

namespace seqc::compiler {
namespace {

using Kind = YamlNode::Kind;

class YamlTreeTest : public ::testing::Test {
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

TEST_F(YamlTreeTest, BlockMapWithLocations) {
  const auto root = load("name: walk\nsteps:\n  - pose: stand\n    time: 500ms\n");
  ASSERT_TRUE(root) << rendered();
  EXPECT_EQ(rendered(), "");
  ASSERT_TRUE(root->is_map());
  EXPECT_EQ(root->location, at(1, 1));
  ASSERT_EQ(root->entries.size(), 2u);
  EXPECT_EQ(root->entries[0].first.scalar, "name");
  EXPECT_EQ(root->entries[0].first.location, at(1, 1));
  EXPECT_EQ(root->entries[0].second.location, at(1, 7));
  const YamlNode* steps = root->find("steps");
  ASSERT_NE(steps, nullptr);
  ASSERT_TRUE(steps->is_sequence());
  EXPECT_EQ(steps->location, at(3, 3));
  ASSERT_EQ(steps->items.size(), 1u);
  const YamlNode& step = steps->items[0];
  EXPECT_EQ(step.location, at(3, 5));
  ASSERT_NE(step.find("time"), nullptr);
  EXPECT_EQ(step.find("time")->scalar, "500ms");
  EXPECT_EQ(step.find("time")->location, at(4, 11));
  EXPECT_EQ(step.find("nope"), nullptr);
  EXPECT_EQ(steps->find("pose"), nullptr);  // not a map
}

TEST_F(YamlTreeTest, FlowCollectionsStillWork) {
  const auto root = load("list: [1, 2, 3]\nmap: {a: 1, b: 2}\nempty: []\n");
  ASSERT_TRUE(root) << rendered();
  const YamlNode* list = root->find("list");
  ASSERT_TRUE(list && list->is_sequence());
  ASSERT_EQ(list->items.size(), 3u);
  EXPECT_EQ(list->items[2].scalar, "3");
  EXPECT_EQ(list->items[2].location, at(1, 14));
  const YamlNode* map = root->find("map");
  ASSERT_TRUE(map && map->is_map());
  ASSERT_EQ(map->entries.size(), 2u);
  EXPECT_EQ(map->find("b")->scalar, "2");
  EXPECT_TRUE(root->find("empty")->items.empty());
}

TEST_F(YamlTreeTest, TopLevelFlowDocuments) {
  auto root = load("[1, 2, 3]");
  ASSERT_TRUE(root) << rendered();
  EXPECT_EQ(root->items.size(), 3u);
  root = load("{a: 1, b: 2}");
  ASSERT_TRUE(root) << rendered();
  EXPECT_EQ(root->entries.size(), 2u);
}

TEST_F(YamlTreeTest, QuotedScalarsAreMarked) {
  const auto root =
      load("plain: 500\ndouble: \"500\"\nsingle: 'it''s'\nbang: ! 500\nblock: |\n  text\n");
  ASSERT_TRUE(root) << rendered();
  EXPECT_FALSE(root->find("plain")->quoted);
  EXPECT_TRUE(root->find("double")->quoted);
  EXPECT_EQ(root->find("double")->scalar, "500");
  EXPECT_TRUE(root->find("single")->quoted);
  EXPECT_EQ(root->find("single")->scalar, "it's");
  EXPECT_TRUE(root->find("bang")->quoted);
  EXPECT_TRUE(root->find("block")->quoted);
  EXPECT_EQ(root->find("block")->scalar, "text\n");
  EXPECT_FALSE(root->entries[0].first.quoted);
}

TEST_F(YamlTreeTest, NullsAreNullButQuotedNullIsAString) {
  const auto root = load("a: null\nb: ~\nc:\nd: \"null\"\ne: ''\n");
  ASSERT_TRUE(root) << rendered();
  EXPECT_EQ(root->find("a")->kind, Kind::Null);
  EXPECT_EQ(root->find("b")->kind, Kind::Null);
  EXPECT_EQ(root->find("c")->kind, Kind::Null);
  EXPECT_EQ(root->find("d")->kind, Kind::Scalar);
  EXPECT_EQ(root->find("e")->kind, Kind::Scalar);
  EXPECT_EQ(root->find("e")->scalar, "");
}

TEST_F(YamlTreeTest, EmptyAndCommentOnlyFilesAreOneNull) {
  auto root = load("");
  ASSERT_TRUE(root);
  EXPECT_EQ(root->kind, Kind::Null);
  EXPECT_EQ(root->location, at(1, 1));
  root = load("# nothing here\n\n");
  ASSERT_TRUE(root);
  EXPECT_EQ(root->kind, Kind::Null);
  EXPECT_FALSE(diags_.has_errors());
}

TEST_F(YamlTreeTest, ExplicitDocumentMarkersAreFine) {
  const auto root = load("%YAML 1.2\n---\na: 1\n...\n");
  ASSERT_TRUE(root) << rendered();
  EXPECT_EQ(root->find("a")->location, at(3, 4));
}

TEST_F(YamlTreeTest, ByteOrderMarkAndCrlf) {
  const auto root = load(
      "\xEF\xBB\xBF"
      "a: 1\r\nb: [x, y]\r\n");
  ASSERT_TRUE(root) << rendered();
  EXPECT_EQ(root->entries[0].first.location, at(1, 4));  // after the 3-byte mark
  EXPECT_EQ(root->find("a")->scalar, "1");
  EXPECT_EQ(root->find("b")->items[1].location, at(2, 8));
}

TEST_F(YamlTreeTest, ColumnsCountBytes) {
  const auto root = load("caf\xC3\xA9: x\n");
  ASSERT_TRUE(root) << rendered();
  EXPECT_EQ(root->entries[0].second.location, at(1, 8));
}

TEST_F(YamlTreeTest, NestingUpToTheLimitLoads) {
  YamlLimits limits;
  limits.max_depth = 8;
  ASSERT_TRUE(load("[[[[[[[[x]]]]]]]]", limits)) << rendered();
  ASSERT_TRUE(load("- - - - - - - - x\n", limits)) << rendered();
  EXPECT_FALSE(load("[[[[[[[[[x]]]]]]]]]", limits));
  EXPECT_FALSE(load("- - - - - - - - - x\n", limits));
  EXPECT_EQ(diags_.error_count(), 2u);
}

// The flow-depth pre-scan must not count brackets that are text.
TEST_F(YamlTreeTest, BracketsInTextAreNotNesting) {
  const std::string many(200, '[');
  const std::string text = "comment: 1 # " + many + "\n" + "double: \"" + many + "\"\n" +
                           "single: '" + many + "'\n" + "plain: x" + many + "\n" +
                           "literal: |\n  " + many + "\n\n  " + many + "\n" + "folded: >-\n    " +
                           many + "\n" + "list:\n  - |\n    " + many + "\n  - '" + many + "'\n" +
                           "flow: [\"" + many + "\", '" + many + "', a#b # " + many + "\n  ]\n" +
                           "multiline: \"" + many + "\n  " + many + "\"\n" + "after: [[1]]\n";
  const auto root = load(text);
  ASSERT_TRUE(root) << rendered();
  EXPECT_EQ(root->find("plain")->scalar, "x" + many);
  EXPECT_EQ(root->find("literal")->scalar, many + "\n\n" + many + "\n");
  EXPECT_EQ(root->find("flow")->items[2].scalar, "a#b");
  EXPECT_EQ(root->find("after")->items[0].items[0].scalar, "1");
}

TEST_F(YamlTreeTest, SoftErrorsKeepTheTreeAndAllAreReported) {
  const auto root = load("a: 1\nb: !!str x\na: 2\n? [k]\n: v\nc: 3\n");
  ASSERT_TRUE(root);
  EXPECT_EQ(diags_.error_count(), 3u) << rendered();
  ASSERT_EQ(root->entries.size(), 3u);  // a, b, c: the duplicate and the bad key are left out
  EXPECT_EQ(root->find("a")->scalar, "1");
  EXPECT_EQ(root->find("c")->scalar, "3");
}

}  // namespace
}  // namespace seqc::compiler
