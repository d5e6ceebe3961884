// Positions in UTF-16 code units over UTF-8 text, incremental edits, URIs and the overlay of
// open documents over the disk.
#include <gtest/gtest.h>

#include "runtime/lsp/documents.hpp"
#include "tests/lsp/lsp_test_util.hpp"

namespace seqc::lsp {
namespace {

// "é" is 2 bytes and 1 unit; "😀" (U+1F600) is 4 bytes and 2 units (a surrogate pair).
const std::string kText = "a\xC3\xA9\xF0\x9F\x98\x80z\nsecond\r\nthird";

TEST(LspDocuments, Utf16Length) {
  EXPECT_EQ(utf16_length("abc"), 3u);
  EXPECT_EQ(utf16_length("\xC3\xA9"), 1u);
  EXPECT_EQ(utf16_length("\xF0\x9F\x98\x80"), 2u);
  EXPECT_EQ(utf16_length("\xE2\x82\xAC"), 1u);  // the euro sign
  EXPECT_EQ(utf16_length("\xFF\x80"), 2u);      // no UTF-8: one unit a byte
}

TEST(LspDocuments, OffsetOfCountsUtf16Units) {
  EXPECT_EQ(offset_of(kText, {0, 0}), 0u);
  EXPECT_EQ(offset_of(kText, {0, 1}), 1u);
  EXPECT_EQ(offset_of(kText, {0, 2}), 3u);  // after the é
  EXPECT_EQ(offset_of(kText, {0, 4}), 7u);  // after the surrogate pair
  EXPECT_EQ(offset_of(kText, {0, 3}), 7u);  // inside the pair: its end
  EXPECT_EQ(offset_of(kText, {0, 5}), 8u);
  EXPECT_EQ(offset_of(kText, {0, 99}), 8u);  // past the line: its end
  EXPECT_EQ(offset_of(kText, {1, 6}), 15u);
  EXPECT_EQ(offset_of(kText, {1, 7}), 15u);  // the '\r' of "\r\n" is no character
  EXPECT_EQ(offset_of(kText, {2, 2}), 19u);
  EXPECT_EQ(offset_of(kText, {9, 0}), kText.size());
}

TEST(LspDocuments, IncrementalEditsAroundSurrogatePairs) {
  std::string text = kText;
  apply_edit(text, {0, 4}, {0, 5}, "Z");  // z -> Z, after the pair
  EXPECT_EQ(text, "a\xC3\xA9\xF0\x9F\x98\x80Z\nsecond\r\nthird");
  apply_edit(text, {0, 2}, {0, 4}, "");  // the emoji removed
  EXPECT_EQ(text, "a\xC3\xA9Z\nsecond\r\nthird");
  apply_edit(text, {0, 1}, {1, 3}, "\xF0\x9F\x98\x80");  // across lines
  EXPECT_EQ(text, "a\xF0\x9F\x98\x80ond\r\nthird");
  apply_edit(text, {1, 0}, {1, 0}, "x");
  EXPECT_EQ(text, "a\xF0\x9F\x98\x80ond\r\nxthird");
  apply_edit(text, {0, 4}, {0, 1}, "");  // start after end: swapped
  EXPECT_EQ(text, "and\r\nxthird");
}

TEST(LspDocuments, UrisAndPaths) {
  EXPECT_EQ(uri_to_path("file:///home/me/my%20dance.yaml"), "/home/me/my dance.yaml");
  EXPECT_EQ(uri_to_path("file://localhost/tmp/a.yaml"), "/tmp/a.yaml");
  EXPECT_EQ(uri_to_path("file:///C%3A/x%zz"), "/C:/x%zz");
  EXPECT_EQ(uri_to_path("untitled:Untitled-1"), "untitled:Untitled-1");
  EXPECT_EQ(path_to_uri("/home/me/my dance.yaml"), "file:///home/me/my%20dance.yaml");
  EXPECT_EQ(normal_path("/a/b/../c/./d.yaml"), "/a/c/d.yaml");
}

TEST(LspDocuments, OverlayServesOpenTextsOverTheDisk) {
  test::MemoryFiles disk({{"/p/a.yaml", "on disk"}, {"/p/b.yaml", "b on disk"}});
  DocumentTexts open{{"/p/a.yaml", std::make_shared<const std::string>("typed")}};
  OverlayReader files(open, disk);
  EXPECT_EQ(*files.read("/p/sub/../a.yaml"), "typed");
  EXPECT_EQ(files.size("/p/a.yaml"), 5u);
  EXPECT_EQ(*files.read("/p/b.yaml"), "b on disk");
  EXPECT_FALSE(files.read("/p/c.yaml"));
}

}  // namespace
}  // namespace seqc::lsp
