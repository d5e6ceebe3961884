// `seqc import` and `seqc export` through the binary, on files in a scratch folder: a .d6a
// written with SQLite's own API becomes a choreography that checks, and exports back to the
// same table; an example exports to the rows its language says.
#include <gtest/gtest.h>
#include <sqlite3.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

#include "tests/cli/seqc_run.hpp"

namespace {

namespace fs = std::filesystem;
using seqc::testing::kSource;
using seqc::testing::seqc;
using seqc::testing::SeqcRun;
using Rows = std::vector<std::vector<int>>;  // Time, Servo1..ServoN

void exec(sqlite3* db, const std::string& sql) {
  char* error = nullptr;
  ASSERT_EQ(sqlite3_exec(db, sql.c_str(), nullptr, nullptr, &error), SQLITE_OK)
      << (error ? error : "");
}

void write_table(const fs::path& path, std::size_t columns, const Rows& rows) {
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
  std::string sql = "CREATE TABLE ActionGroup([Index] INTEGER PRIMARY KEY AUTOINCREMENT, Time INT";
  for (std::size_t k = 1; k <= columns; ++k) sql += ", Servo" + std::to_string(k) + " INT";
  exec(db, sql + ")");
  for (const auto& row : rows) {
    std::string insert = "INSERT INTO ActionGroup VALUES (NULL";
    for (int v : row) insert += ", " + std::to_string(v);
    exec(db, insert + ")");
  }
  sqlite3_close(db);
}

Rows read_table(const fs::path& path) {
  sqlite3* db = nullptr;
  Rows rows;
  if (sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READONLY, nullptr) != SQLITE_OK) return rows;
  sqlite3_stmt* s = nullptr;
  sqlite3_prepare_v2(db, "SELECT * FROM ActionGroup ORDER BY [Index]", -1, &s, nullptr);
  while (s != nullptr && sqlite3_step(s) == SQLITE_ROW) {
    std::vector<int> row;
    for (int c = 1; c < sqlite3_column_count(s); ++c) row.push_back(sqlite3_column_int(s, c));
    rows.push_back(row);
  }
  sqlite3_finalize(s);
  sqlite3_close(db);
  return rows;
}

class D6aCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("seqc-d6a-cli-" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(D6aCli, ImportChecksAndExportsBackToTheSameTable) {
  const Rows rows = {
      {1000, 500, 500, 500, 500, 500, 500, 500, 500}, {400, 420, 500, 580, 500, 500, 500, 500, 500},
      {400, 420, 500, 580, 500, 600, 400, 500, 500},  {250, 420, 500, 580, 500, 600, 400, 500, 500},
      {600, 500, 500, 500, 500, 500, 500, 500, 500},
  };
  write_table(dir_ / "crab.d6a", 8, rows);
  const SeqcRun imported = seqc(dir_, "import crab.d6a -o crab.yaml");
  ASSERT_EQ(imported.status, 0) << imported.err;
  EXPECT_EQ(imported.err, "seqc: crab.yaml: 5 steps from crab.d6a\n");
  const SeqcRun checked = seqc(dir_, "check crab.yaml");
  EXPECT_EQ(checked.status, 0) << checked.err;
  EXPECT_EQ(checked.out.rfind("crab.yaml: 5/1020 actions, 2.650 s", 0), 0u) << checked.out;
  const SeqcRun exported = seqc(dir_, "export crab.yaml");
  ASSERT_EQ(exported.status, 0) << exported.err;
  EXPECT_EQ(exported.err, "seqc: crab.d6a: 5 actions, Servo1..Servo8\n");  // crab.d6a replaced
  EXPECT_EQ(read_table(dir_ / "crab.d6a"), rows);
  // The choreography on stdout when no -o is given.
  EXPECT_NE(seqc(dir_, "import crab.d6a").out.find("robot:\n  profile: bus\n"), std::string::npos);
}

TEST_F(D6aCli, AnExampleExportsTheActionsItsLanguageSays) {
  // walk.yaml begins `move: home, time: 1s` then `move: ready, time: 800ms` (claw 300,
  // wrist_roll 500, wrist_pitch 300, elbow 650, shoulder 400, base 500).
  const SeqcRun r =
      seqc(kSource, "export tests/data/walk-joints.yaml -o '" + (dir_ / "walk.d6a").string() + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  const Rows rows = read_table(dir_ / "walk.d6a");
  ASSERT_EQ(rows.size(), 27u);
  EXPECT_EQ(rows[0], (std::vector<int>{1000, 500, 500, 500, 500, 500, 500}));
  EXPECT_EQ(rows[1], (std::vector<int>{800, 300, 500, 300, 650, 400, 500}));
}

TEST_F(D6aCli, ForeignFilesAreClearErrors) {
  const SeqcRun r = seqc(kSource, "import tests/data/walk-joints.yaml");
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.err,
            "seqc: error: tests/data/walk-joints.yaml: not a SQLite database (a .d6a file is one; this file "
            "does not start with \"SQLite format 3\")\n");
  const SeqcRun car = seqc(kSource, "export examples/car-dance.yaml -o -");
  EXPECT_EQ(car.status, 1);
  EXPECT_NE(car.err.find("a Raspblock program is a live stream"), std::string::npos) << car.err;
}

}  // namespace
