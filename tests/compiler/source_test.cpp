#include "base/source.hpp"

#include <gtest/gtest.h>

namespace seqc::compiler {
namespace {

TEST(SourceManager, AddsFilesAndReturnsTheirIndexes) {
  SourceManager sm;
  EXPECT_EQ(sm.add("a.yaml", "x"), 0u);
  EXPECT_EQ(sm.add("b.yaml", "y"), 1u);
  EXPECT_EQ(sm.file_count(), 2u);
  EXPECT_EQ(sm.path(1), "b.yaml");
  EXPECT_EQ(sm.text(0), "x");
}

TEST(SourceManager, QuotesLinesWithoutTheirLineEnds) {
  SourceManager sm;
  const auto f = sm.add("a.yaml", "one\ntwo\r\n\nfour");
  EXPECT_EQ(sm.line(f, 1), "one");
  EXPECT_EQ(sm.line(f, 2), "two");
  EXPECT_EQ(sm.line(f, 3), "");
  EXPECT_EQ(sm.line(f, 4), "four");
  EXPECT_EQ(sm.line_count(f), 4u);
}

TEST(SourceManager, OutOfRangeLinesAndFilesAreEmpty) {
  SourceManager sm;
  const auto f = sm.add("a.yaml", "one\n");
  EXPECT_EQ(sm.line_count(f), 2u);  // the final '\n' starts an empty line 2
  EXPECT_EQ(sm.line(f, 2), "");
  EXPECT_EQ(sm.line(f, 0), "");
  EXPECT_EQ(sm.line(f, 3), "");
  EXPECT_EQ(sm.line(7, 1), "");
  EXPECT_EQ(sm.path(7), "");
  EXPECT_EQ(sm.line_count(7), 0u);
}

TEST(SourceManager, EmptyFileHasOneEmptyLine) {
  SourceManager sm;
  const auto f = sm.add("empty.yaml", "");
  EXPECT_EQ(sm.line_count(f), 1u);
  EXPECT_EQ(sm.line(f, 1), "");
}

}  // namespace
}  // namespace seqc::compiler
