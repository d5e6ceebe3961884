// write_golden, the one place goldens are written under SEQC_UPDATE_GOLDEN=1: in a scratch
// folder, an unchanged file is neither touched nor reported, and every created or rewritten
// file is reported with its path, +added/-removed line counts and its first differing lines.
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "tests/golden_update.hpp"

namespace seqc::testing {
namespace {

namespace fs = std::filesystem;

std::string read(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

class WriteGolden : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("seqc-golden-update-" + std::to_string(::getpid()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  void put(const fs::path& p, const std::string& text) {
    std::ofstream(p, std::ios::binary) << text;
  }

  fs::path dir_;
};

TEST_F(WriteGolden, UnchangedContentIsNeitherWrittenNorReported) {
  const fs::path file = dir_ / "same.txt";
  put(file, "one\ntwo\n");
  fs::last_write_time(file, fs::file_time_type::clock::now() - std::chrono::hours(24));
  const fs::file_time_type old_time = fs::last_write_time(file);
  std::ostringstream report;
  EXPECT_EQ(write_golden(file, "one\ntwo\n", report), GoldenWrite::Unchanged);
  EXPECT_EQ(report.str(), "");
  EXPECT_EQ(fs::last_write_time(file), old_time);
  EXPECT_EQ(read(file), "one\ntwo\n");
}

TEST_F(WriteGolden, ANewFileIsCreatedWithItsFolderAndReported) {
  const fs::path file = dir_ / "sub" / "new.txt";
  std::ostringstream report;
  EXPECT_EQ(write_golden(file, "a\nb\n", report), GoldenWrite::Created);
  EXPECT_EQ(read(file), "a\nb\n");
  EXPECT_EQ(report.str(), "golden created: " + file.string() +
                              " (+2 -0 lines)\n"
                              "  + a\n"
                              "  + b\n");
}

TEST_F(WriteGolden, AChangedLineIsReportedWithItsPathCountsAndLines) {
  const fs::path file = dir_ / "changed.txt";
  put(file, "keep 1\nold\nkeep 2\n");
  std::ostringstream report;
  EXPECT_EQ(write_golden(file, "keep 1\nnew\nkeep 2\n", report), GoldenWrite::Rewritten);
  EXPECT_EQ(read(file), "keep 1\nnew\nkeep 2\n");
  EXPECT_EQ(report.str(), "golden rewritten: " + file.string() +
                              " (+1 -1 lines)\n"
                              "  first difference at line 2:\n"
                              "  - old\n"
                              "  + new\n");
}

TEST_F(WriteGolden, AnInsertedLineCountsOnceNotAsEveryLineAfterIt) {
  const fs::path file = dir_ / "inserted.txt";
  put(file, "1\n2\n3\n4\n5\n6\n");
  std::ostringstream report;
  EXPECT_EQ(write_golden(file, "1\n2\nX\n3\n4\n5\n6\n", report), GoldenWrite::Rewritten);
  EXPECT_NE(report.str().find(" (+1 -0 lines)\n  first difference at line 3:\n"), std::string::npos)
      << report.str();
}

TEST_F(WriteGolden, ScatteredChangesAreCountedAndTheFirstLinesShown) {
  const fs::path file = dir_ / "scattered.txt";
  put(file, "a\nb\nc\nd\ne\nf\ng\n");
  std::ostringstream report;
  // b removed, d changed to D, two lines added at the end.
  EXPECT_EQ(write_golden(file, "a\nc\nD\ne\nf\ng\nh\ni\n", report), GoldenWrite::Rewritten);
  EXPECT_EQ(report.str(), "golden rewritten: " + file.string() +
                              " (+3 -2 lines)\n"
                              "  first difference at line 2:\n"
                              "  - b\n"
                              "  - c\n"
                              "  - d\n"
                              "  + c\n"
                              "  + D\n"
                              "  + e\n");
}

TEST_F(WriteGolden, ALostFinalNewlineIsAChange) {
  const fs::path file = dir_ / "newline.txt";
  put(file, "x\ny\n");
  std::ostringstream report;
  EXPECT_EQ(write_golden(file, "x\ny", report), GoldenWrite::Rewritten);
  EXPECT_EQ(read(file), "x\ny");
  EXPECT_EQ(report.str(), "golden rewritten: " + file.string() +
                              " (+1 -1 lines)\n"
                              "  first difference at line 2:\n"
                              "  - y\n"
                              "  + y\n"
                              "  \\ no newline at end of file\n");
}

TEST_F(WriteGolden, AFileThatCannotBeWrittenIsAFailure) {
  put(dir_ / "plain", "not a folder\n");
  const fs::path file = dir_ / "plain" / "golden.txt";
  std::ostringstream report;
  EXPECT_EQ(write_golden(file, "text\n", report), GoldenWrite::Failed);
  EXPECT_NE(report.str().find("golden NOT written: " + file.string()), std::string::npos)
      << report.str();
}

TEST(UpdatingGoldens, OnlyTheValueOneTurnsItOn) {
  const char* saved = std::getenv("SEQC_UPDATE_GOLDEN");
  const std::string keep = saved ? saved : "";
  ::unsetenv("SEQC_UPDATE_GOLDEN");
  EXPECT_FALSE(updating_goldens());
  ::setenv("SEQC_UPDATE_GOLDEN", "0", 1);
  EXPECT_FALSE(updating_goldens());
  ::setenv("SEQC_UPDATE_GOLDEN", "yes", 1);
  EXPECT_FALSE(updating_goldens());
  ::setenv("SEQC_UPDATE_GOLDEN", "1", 1);
  EXPECT_TRUE(updating_goldens());
  if (saved) {
    ::setenv("SEQC_UPDATE_GOLDEN", keep.c_str(), 1);
  } else {
    ::unsetenv("SEQC_UPDATE_GOLDEN");
  }
}

}  // namespace
}  // namespace seqc::testing
