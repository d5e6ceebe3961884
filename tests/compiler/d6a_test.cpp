// .d6a action files: tables built here with SQLite's own API (as Hiwonder's tools write them,
// not by seqc's writer) are imported, compiled, and exported again. The compiled actions must
// equal the rows, and export must give back the table the test wrote.
#include <gtest/gtest.h>
#include <sqlite3.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "compiler/formats/d6a.hpp"
#include "compiler/formats/d6a_import.hpp"
#include "tests/compiler/lang_test_util.hpp"

namespace seqc {
namespace {

using compiler::D6aRow;
using compiler::D6aTable;

// Writes rows into a new SQLite file at `path` with the statements Hiwonder's tools use, and
// returns its bytes.
std::string sqlite_file(const std::string& path, std::size_t columns,
                        const std::vector<std::pair<int, std::vector<int>>>& rows,
                        const std::string& create = "") {
  std::filesystem::remove(path);
  sqlite3* db = nullptr;
  EXPECT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
  std::string sql = create;
  if (sql.empty()) {
    sql = "CREATE TABLE ActionGroup([Index] INTEGER PRIMARY KEY AUTOINCREMENT, Time INT";
    for (std::size_t k = 1; k <= columns; ++k) sql += ", Servo" + std::to_string(k) + " INT";
    sql += ");";
  }
  for (const auto& [time, positions] : rows) {
    sql += "INSERT INTO ActionGroup (Time";
    for (std::size_t k = 1; k <= columns; ++k) sql += ", Servo" + std::to_string(k);
    sql += ") VALUES (" + std::to_string(time);
    for (int p : positions) sql += ", " + std::to_string(p);
    sql += ");";
  }
  char* error = nullptr;
  EXPECT_EQ(sqlite3_exec(db, sql.c_str(), nullptr, nullptr, &error), SQLITE_OK)
      << (error ? error : "");
  sqlite3_free(error);
  sqlite3_close(db);
  std::ifstream in(path, std::ios::binary);
  std::stringstream bytes;
  bytes << in.rdbuf();
  std::filesystem::remove(path);
  return bytes.str();
}

std::string temp_path(const std::string& name) {
  return (std::filesystem::temp_directory_path() /
          ("seqc-d6a-" + std::to_string(::getpid()) + "-" + name))
      .string();
}

// A humanoid-shaped walk: 16 servos, 40 rows of 80-600 ms, a few servos moving per row, some
// rows that change nothing (holds), as Hiwonder's humanoid action files look.
std::vector<std::pair<int, std::vector<int>>> humanoid_rows() {
  std::vector<std::pair<int, std::vector<int>>> rows;
  std::vector<int> pose(16, 500);
  for (int r = 0; r < 40; ++r) {
    if (r % 7 != 6) {  // every seventh row holds
      for (int k = 0; k < 16; ++k) {
        if ((k + r) % 4 == 0) pose[k] = 350 + (k * 37 + r * 53) % 300;
      }
    }
    rows.push_back({80 + (r * 67) % 520, pose});
  }
  return rows;
}

// The compiled actions replayed: each keyframe's time and every servo's position after it.
std::vector<std::pair<int, std::vector<int>>> replay(const compiler::ServoProgram& p,
                                                     std::size_t columns) {
  std::vector<std::pair<int, std::vector<int>>> out;
  std::vector<int> now(columns, -1);
  for (const compiler::Keyframe& k : p.keyframes) {
    for (const lsc::ServoTarget& t : k.targets) now[t.id - 1] = t.position;
    out.push_back({k.time_ms, now});
  }
  return out;
}

TEST(D6a, HumanoidImportCompilesToTheRowsAndExportsTheSameTable) {
  const auto rows = humanoid_rows();
  const std::string bytes = sqlite_file(temp_path("humanoid.d6a"), 16, rows);
  auto table = compiler::read_d6a(bytes);
  ASSERT_TRUE(table.ok()) << table.error().message;
  EXPECT_EQ(table->servo_columns, 16u);
  ASSERT_EQ(table->rows.size(), rows.size());

  auto yaml = compiler::choreography_from_d6a(*table, {"humanoid", "humanoid.d6a", ""});
  ASSERT_TRUE(yaml.ok()) << yaml.error().message;
  EXPECT_NE(yaml->find("profile: bus"), std::string::npos) << *yaml;
  const compiler::CompileOutput out = compiler::testing::compile_text(*yaml);
  const compiler::ServoProgram& program = compiler::testing::program_of(out);
  // One action per row, the row's time, every servo where the row puts it.
  EXPECT_EQ(replay(program, 16), rows) << *yaml;

  auto exported = compiler::d6a_from_program(program);
  ASSERT_TRUE(exported.ok()) << exported.error().message;
  auto written = compiler::write_d6a(*exported);
  ASSERT_TRUE(written.ok());
  auto again = compiler::read_d6a(*written);
  ASSERT_TRUE(again.ok()) << again.error().message;
  EXPECT_EQ(again->servo_columns, 16u);
  ASSERT_EQ(again->rows.size(), rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    EXPECT_EQ(again->rows[i].index, static_cast<std::int64_t>(i + 1));
    EXPECT_EQ(again->rows[i].time_ms, rows[i].first) << i;
    EXPECT_EQ(again->rows[i].positions, rows[i].second) << i;
  }
}

TEST(D6a, SixColumnsBecomeAnXArmWithItsServoNames) {
  const std::vector<std::pair<int, std::vector<int>>> rows = {
      {1000, {500, 500, 500, 500, 500, 500}},
      {800, {300, 500, 300, 650, 400, 500}},
      {600, {300, 500, 300, 650, 400, 750}},
      {300, {300, 500, 300, 650, 400, 750}},
  };
  auto table = compiler::read_d6a(sqlite_file(temp_path("arm.d6a"), 6, rows));
  ASSERT_TRUE(table.ok()) << table.error().message;
  auto yaml = compiler::choreography_from_d6a(*table, {"arm", "arm.d6a", ""});
  ASSERT_TRUE(yaml.ok());
  EXPECT_NE(yaml->find("robot: xarm\n"), std::string::npos);
  EXPECT_NE(yaml->find("  - move: {base: 750}  # row 3\n    time: 600ms\n"), std::string::npos)
      << *yaml;
  EXPECT_NE(yaml->find("  - wait: 300ms"), std::string::npos) << *yaml;
  const compiler::CompileOutput out = compiler::testing::compile_text(*yaml);
  EXPECT_EQ(replay(compiler::testing::program_of(out), 6), rows);
  auto exported = compiler::d6a_from_program(compiler::testing::program_of(out));
  ASSERT_TRUE(exported.ok());
  EXPECT_EQ(exported->servo_columns, 6u);
}

TEST(D6a, ForeignOrBrokenFilesSayWhatIsMissing) {
  EXPECT_EQ(compiler::read_d6a("robot: xarm\n").error().message,
            "not a SQLite database (a .d6a file is one; this file does not start with \"SQLite "
            "format 3\")");
  EXPECT_EQ(compiler::read_d6a(sqlite_file(temp_path("other.db"), 0, {},
                                           "CREATE TABLE Notes(a INT); CREATE TABLE Poses(b INT);"))
                .error()
                .message,
            "no ActionGroup table (a .d6a file has one; this database has the tables Notes, "
            "Poses)");
  EXPECT_EQ(compiler::read_d6a(
                sqlite_file(temp_path("notime.d6a"), 0, {},
                            "CREATE TABLE ActionGroup([Index] INTEGER PRIMARY KEY, Servo1 INT);"))
                .error()
                .message,
            "the ActionGroup table has no Time column");
  EXPECT_EQ(compiler::read_d6a(sqlite_file(temp_path("gap.d6a"), 0, {},
                                           "CREATE TABLE ActionGroup([Index] INTEGER PRIMARY KEY, "
                                           "Time INT, Servo1 INT, Servo3 INT);"))
                .error()
                .message,
            "the ActionGroup table has Servo3 but no Servo2 column");
  // A truncated database: SQLite itself finds the damage.
  std::string cut = sqlite_file(temp_path("cut.d6a"), 6, {{100, {1, 2, 3, 4, 5, 6}}});
  cut.resize(cut.size() / 2);
  EXPECT_FALSE(compiler::read_d6a(cut).ok());
}

TEST(D6a, RowsThatCannotBeActionsAreErrorsWithTheirRow) {
  auto table = compiler::read_d6a(
      sqlite_file(temp_path("bad.d6a"), 6,
                  {{1000, {500, 500, 500, 500, 500, 500}}, {10, {500, 500, 500, 500, 500, 500}}}));
  ASSERT_TRUE(table.ok());
  EXPECT_EQ(compiler::choreography_from_d6a(*table, {"bad", "bad.d6a", ""}).error().message,
            "row 2 (Index 2): Time 10 ms is outside the controller's 20-30000 ms per action");
  table->rows[1].time_ms = 500;
  table->rows[1].positions[2] = 1200;
  EXPECT_EQ(compiler::choreography_from_d6a(*table, {"bad", "bad.d6a", ""}).error().message,
            "row 2 (Index 2): Servo3 is 1200, outside xarm's 0-1000");
  EXPECT_EQ(
      compiler::choreography_from_d6a(*table, {"bad", "bad.d6a", "raspblock"}).error().message,
      "--robot raspblock: not a servo controller profile (xarm, bus, lsc-16, lsc-32, lsc-6, "
      "learm, raspblock)");
}

// The bytes of a database made in memory by `sql` (hostile files are built with SQLite itself).
std::string database(const std::string& sql) {
  sqlite3* db = nullptr;
  EXPECT_EQ(sqlite3_open(":memory:", &db), SQLITE_OK);
  char* error = nullptr;
  EXPECT_EQ(sqlite3_exec(db, sql.c_str(), nullptr, nullptr, &error), SQLITE_OK)
      << (error ? error : "");
  sqlite3_free(error);
  sqlite3_int64 size = 0;
  unsigned char* data = sqlite3_serialize(db, "main", &size, 0);
  std::string bytes(reinterpret_cast<const char*>(data), static_cast<std::size_t>(size));
  sqlite3_free(data);
  sqlite3_close(db);
  return bytes;
}

constexpr char kTable[] =
    "CREATE TABLE ActionGroup([Index] INTEGER PRIMARY KEY AUTOINCREMENT, Time INT, Servo1 INT);";
constexpr char kRefusedTail[] =
    " (a .d6a file is one plain table; seqc reads no views, triggers or virtual tables)";

TEST(D6a, ViewsTriggersAndVirtualTablesAreRefusedByName) {
  // A view whose rows never end (a recursive CTE) stands where the table should be.
  EXPECT_EQ(
      compiler::read_d6a(database("CREATE VIEW ActionGroup([Index], Time, Servo1) AS "
                                  "WITH RECURSIVE n(i) AS (SELECT 1 UNION ALL SELECT i + 1 FROM "
                                  "n) SELECT i, 100, 500 FROM n;"))
          .error()
          .message,
      std::string("the database holds a view, ActionGroup") + kRefusedTail);
  EXPECT_EQ(compiler::read_d6a(database(std::string(kTable) +
                                        "CREATE VIEW extra AS SELECT 1; "
                                        "INSERT INTO ActionGroup (Time, Servo1) VALUES (100, 1);"))
                .error()
                .message,
            std::string("the database holds a view, extra") + kRefusedTail);
  EXPECT_EQ(compiler::read_d6a(database(std::string(kTable) +
                                        "CREATE TRIGGER grow AFTER INSERT ON ActionGroup BEGIN "
                                        "INSERT INTO ActionGroup (Time, Servo1) VALUES (1, 1); "
                                        "END;"))
                .error()
                .message,
            std::string("the database holds a trigger, grow") + kRefusedTail);
  EXPECT_EQ(compiler::read_d6a(database("CREATE VIRTUAL TABLE ActionGroup USING "
                                        "fts5(Idx, Time, Servo1);"))
                .error()
                .message,
            std::string("the database holds a virtual table, ActionGroup") + kRefusedTail);
}

TEST(D6a, AMillionRowsAreRefusedAtTheRowLimit) {
  const std::string bytes =
      database(std::string(kTable) +
               "WITH RECURSIVE n(i) AS (SELECT 1 UNION ALL SELECT i + 1 FROM n WHERE i < 1000000) "
               "INSERT INTO ActionGroup (Time, Servo1) SELECT 100, 500 FROM n;");
  EXPECT_EQ(compiler::read_d6a(bytes).error().message,
            "the ActionGroup table has more than 65536 rows, the most seqc reads");
  // Exactly the limit is read.
  compiler::D6aReadLimits limits;
  limits.max_rows = 3;
  const std::string three =
      database(std::string(kTable) +
               "INSERT INTO ActionGroup (Time, Servo1) VALUES (100, 1), (100, 2), (100, 3);");
  EXPECT_EQ(compiler::read_d6a(three, limits)->rows.size(), 3u);
  limits.max_rows = 2;
  EXPECT_EQ(compiler::read_d6a(three, limits).error().message,
            "the ActionGroup table has more than 2 rows, the most seqc reads");
}

TEST(D6a, SqliteIsInterruptedPastItsStepBudget) {
  // No [Index] key, rows stored in reverse: read in stored order, returned in [Index] order.
  const std::string reversed = database(
      "CREATE TABLE ActionGroup([Index] INT, Time INT, Servo1 INT);"
      "WITH RECURSIVE n(i) AS (SELECT 1 UNION ALL SELECT i + 1 FROM n WHERE i < 20000) "
      "INSERT INTO ActionGroup SELECT 20001 - i, 100 + i % 7, 500 FROM n;");
  compiler::D6aReadLimits limits;
  limits.max_steps = 10'000;
  EXPECT_EQ(compiler::read_d6a(reversed, limits).error().message,
            "reading it took more than 10000 SQLite steps, the most seqc spends on a .d6a file");
  auto table = compiler::read_d6a(reversed);
  ASSERT_TRUE(table.ok()) << table.error().message;
  ASSERT_EQ(table->rows.size(), 20000u);
  // Row k (from 0) has [Index] k + 1 and was inserted as i = 20000 - k: Time 100 + i % 7.
  for (std::size_t k = 0; k < 20000; ++k) {
    ASSERT_EQ(table->rows[k].index, std::int64_t(k + 1)) << k;
    ASSERT_EQ(table->rows[k].time_ms, int(100 + (20000 - k) % 7)) << k;
  }
}

// The names a file brings when none is given: its own, or for standard input fixed ones.
TEST(D6a, NamesComeFromThePathOrStandardInput) {
  const compiler::ImportOptions from_file =
      compiler::import_options_for("moves/wave.d6a", "<stdin>", "bus");
  EXPECT_EQ(from_file.name, "wave");
  EXPECT_EQ(from_file.source, "wave.d6a");
  EXPECT_EQ(from_file.profile, "bus");
  const compiler::ImportOptions from_stdin = compiler::import_options_for("-", "<stdin>", "");
  EXPECT_EQ(from_stdin.name, "imported");
  EXPECT_EQ(from_stdin.source, "<stdin>");
  EXPECT_EQ(compiler::d6a_output_name("dances/walk.yaml", 3), "walk.d6a");
  EXPECT_EQ(compiler::d6a_output_name("-", 3), "group3.d6a");
}

}  // namespace
}  // namespace seqc
