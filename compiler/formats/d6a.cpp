#include "compiler/formats/d6a.hpp"

#include <sqlite3.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>

namespace seqc::compiler {
namespace {

struct DbCloser {
  void operator()(sqlite3* db) const { sqlite3_close(db); }
};
using Db = std::unique_ptr<sqlite3, DbCloser>;
struct StmtFinalizer {
  void operator()(sqlite3_stmt* s) const { sqlite3_finalize(s); }
};
using Stmt = std::unique_ptr<sqlite3_stmt, StmtFinalizer>;

Result<Stmt> prepare(sqlite3* db, const std::string& sql) {
  sqlite3_stmt* raw = nullptr;
  if (sqlite3_prepare_v2(db, sql.c_str(), -1, &raw, nullptr) != SQLITE_OK) {
    return make_error(sqlite3_errmsg(db));
  }
  return Stmt(raw);
}

Result<Db> open_memory() {
  sqlite3* raw = nullptr;
  if (sqlite3_open(":memory:", &raw) != SQLITE_OK) {
    Db guard(raw);
    return make_error("SQLite cannot open an in-memory database");
  }
  return Db(raw);
}

// "Servo12" -> 12, anything else -> 0.
std::size_t servo_number(const std::string& column) {
  if (column.size() < 6 || column.compare(0, 5, "Servo") != 0) return 0;
  std::size_t n = 0;
  for (std::size_t i = 5; i < column.size(); ++i) {
    if (column[i] < '0' || column[i] > '9') return 0;
    n = n * 10 + static_cast<std::size_t>(column[i] - '0');
    if (n > 255) return 0;
  }
  return column[5] == '0' ? 0 : n;
}

// A whole number in a cell, as Hiwonder's tools store them (INTEGER, or text of digits).
std::optional<std::int64_t> whole(sqlite3_stmt* s, int column) {
  switch (sqlite3_column_type(s, column)) {
    case SQLITE_INTEGER:
      return sqlite3_column_int64(s, column);
    case SQLITE_FLOAT: {
      const double d = sqlite3_column_double(s, column);
      if (d == static_cast<double>(static_cast<std::int64_t>(d)))
        return static_cast<std::int64_t>(d);
      return std::nullopt;
    }
    default:
      return std::nullopt;
  }
}

// Called by SQLite every kStepsPerCall instructions; a nonzero return interrupts the statement.
constexpr int kStepsPerCall = 1000;
struct StepBudget {
  std::uint64_t calls_left = 0;
  bool spent = false;
};
int over_budget(void* user) {
  auto* budget = static_cast<StepBudget*>(user);
  if (budget->calls_left == 0) {
    budget->spent = true;
    return 1;
  }
  --budget->calls_left;
  return 0;
}

// Before any query: nothing the file's schema names runs unasked, nothing goes to a temporary
// file, and a view, trigger or virtual table is refused by name (a view's rows can be endless, a
// trigger or a virtual table runs code the file chose).
Status guard(sqlite3* db) {
  int off = 0;
  sqlite3_db_config(db, SQLITE_DBCONFIG_TRUSTED_SCHEMA, 0, &off);
  sqlite3_db_config(db, SQLITE_DBCONFIG_DEFENSIVE, 1, &off);
  sqlite3_db_config(db, SQLITE_DBCONFIG_ENABLE_TRIGGER, 0, &off);
  sqlite3_db_config(db, SQLITE_DBCONFIG_ENABLE_VIEW, 0, &off);
  if (sqlite3_exec(db, "PRAGMA temp_store = MEMORY", nullptr, nullptr, nullptr) != SQLITE_OK) {
    return make_error(std::string("SQLite: ") + sqlite3_errmsg(db));
  }
  auto schema = prepare(db,
                        "SELECT type, name FROM sqlite_master WHERE type IN ('view', 'trigger') "
                        "OR (type = 'table' AND sql LIKE 'CREATE VIRTUAL TABLE%') LIMIT 1");
  if (!schema) return make_error("a corrupt SQLite database: " + schema.error().message);
  if (sqlite3_step(schema->get()) == SQLITE_ROW) {
    const auto* type = sqlite3_column_text(schema->get(), 0);
    const auto* name = sqlite3_column_text(schema->get(), 1);
    std::string kind = type ? reinterpret_cast<const char*>(type) : "";
    if (kind == "table") kind = "virtual table";
    return make_error("the database holds a " + kind + ", " +
                      (name ? reinterpret_cast<const char*>(name) : "") +
                      " (a .d6a file is one plain table; seqc reads no views, triggers or "
                      "virtual tables)");
  }
  return Ok{};
}

}  // namespace

Result<D6aTable> read_d6a(std::string_view bytes, const D6aReadLimits& limits) {
  static constexpr char kMagic[] = "SQLite format 3";  // the 16-byte header, NUL included
  if (bytes.size() < sizeof kMagic || std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0) {
    return make_error(
        "not a SQLite database (a .d6a file is one; this file does not start "
        "with \"SQLite format 3\")");
  }
  auto db = open_memory();
  if (!db) return db.error();
  auto* copy = static_cast<unsigned char*>(sqlite3_malloc64(bytes.size()));
  if (copy == nullptr) return make_error("out of memory reading the file");
  std::memcpy(copy, bytes.data(), bytes.size());
  if (sqlite3_deserialize(db->get(), "main", copy, static_cast<sqlite3_int64>(bytes.size()),
                          static_cast<sqlite3_int64>(bytes.size()),
                          SQLITE_DESERIALIZE_FREEONCLOSE | SQLITE_DESERIALIZE_READONLY) !=
      SQLITE_OK) {
    return make_error(std::string("SQLite cannot read it: ") + sqlite3_errmsg(db->get()));
  }
  // Every step counts: the handler runs every kStepsPerCall instructions.
  StepBudget budget{limits.max_steps / kStepsPerCall};
  sqlite3_progress_handler(db->get(), kStepsPerCall, over_budget, &budget);
  if (Status guarded = guard(db->get()); !guarded) return guarded.error();
  auto interrupted = [&]() -> std::optional<Error> {
    if (!budget.spent) return std::nullopt;
    return make_error("reading it took more than " + std::to_string(limits.max_steps) +
                      " SQLite steps, the most seqc spends on a .d6a file");
  };

  auto columns = prepare(db->get(), "PRAGMA table_info(ActionGroup)");
  if (!columns) return make_error("a corrupt SQLite database: " + columns.error().message);
  bool has_time = false;
  bool has_index = false;
  std::map<std::size_t, std::string> servos;
  while (sqlite3_step(columns->get()) == SQLITE_ROW) {
    const auto* text = sqlite3_column_text(columns->get(), 1);
    const std::string name = text ? reinterpret_cast<const char*>(text) : "";
    if (name == "Time") has_time = true;
    if (name == "Index") has_index = true;
    if (const std::size_t k = servo_number(name)) servos[k] = name;
  }
  if (auto spent = interrupted()) return *spent;
  if (servos.empty() && !has_time && !has_index) {
    std::string tables;
    if (auto list = prepare(db->get(), "SELECT name FROM sqlite_master WHERE type = 'table'")) {
      while (sqlite3_step(list->get()) == SQLITE_ROW) {
        const auto* t = sqlite3_column_text(list->get(), 0);
        tables +=
            std::string(tables.empty() ? "" : ", ") + (t ? reinterpret_cast<const char*>(t) : "");
      }
    } else {
      return make_error("a corrupt SQLite database: " + list.error().message);
    }
    return make_error("no ActionGroup table (a .d6a file has one; this database has " +
                      (tables.empty() ? std::string("no tables") : "the tables " + tables) + ")");
  }
  if (!has_index) return make_error("the ActionGroup table has no [Index] column");
  if (!has_time) return make_error("the ActionGroup table has no Time column");
  if (servos.empty()) return make_error("the ActionGroup table has no Servo1.. columns");
  D6aTable table;
  table.servo_columns = servos.rbegin()->first;
  for (std::size_t k = 1; k <= table.servo_columns; ++k) {
    if (!servos.count(k)) {
      return make_error("the ActionGroup table has Servo" + std::to_string(table.servo_columns) +
                        " but no Servo" + std::to_string(k) + " column");
    }
  }

  std::string sql = "SELECT [Index], Time";
  for (std::size_t k = 1; k <= table.servo_columns; ++k) sql += ", Servo" + std::to_string(k);
  // In stored order, sorted here: ORDER BY on a column that is not the table's key would sort
  // every row inside SQLite (where no step budget reaches) before the row limit could stop it.
  sql += " FROM ActionGroup";
  auto rows = prepare(db->get(), sql);
  if (!rows) return make_error("cannot read ActionGroup: " + rows.error().message);
  int step = SQLITE_ROW;
  while ((step = sqlite3_step(rows->get())) == SQLITE_ROW) {
    if (table.rows.size() == limits.max_rows) {
      return make_error("the ActionGroup table has more than " + std::to_string(limits.max_rows) +
                        " rows, the most seqc reads");
    }
    D6aRow row;
    const auto index = whole(rows->get(), 0);
    const auto time = whole(rows->get(), 1);
    const std::string where = "row " + std::to_string(table.rows.size() + 1);
    if (!index) return make_error(where + ": [Index] is not a whole number");
    row.index = *index;
    if (!time || *time < 0 || *time > 65535) {
      return make_error(where + " (Index " + std::to_string(row.index) +
                        "): Time is not a whole number of milliseconds 0-65535");
    }
    row.time_ms = static_cast<int>(*time);
    for (std::size_t k = 1; k <= table.servo_columns; ++k) {
      const auto v = whole(rows->get(), static_cast<int>(k + 1));
      if (!v || *v < -32768 || *v > 32767) {
        return make_error(where + " (Index " + std::to_string(row.index) + "): Servo" +
                          std::to_string(k) + " is not a whole number");
      }
      row.positions.push_back(static_cast<int>(*v));
    }
    table.rows.push_back(std::move(row));
  }
  if (auto spent = interrupted()) return *spent;
  if (step != SQLITE_DONE) {
    return make_error(std::string("a corrupt SQLite database: ") + sqlite3_errmsg(db->get()));
  }
  std::stable_sort(table.rows.begin(), table.rows.end(),
                   [](const D6aRow& a, const D6aRow& b) { return a.index < b.index; });
  return table;
}

Result<std::string> write_d6a(const D6aTable& table) {
  auto db = open_memory();
  if (!db) return db.error();
  std::string create =
      "CREATE TABLE ActionGroup([Index] INTEGER PRIMARY KEY AUTOINCREMENT, Time INT";
  std::string insert = "INSERT INTO ActionGroup VALUES (?, ?";
  for (std::size_t k = 1; k <= table.servo_columns; ++k) {
    create += ", Servo" + std::to_string(k) + " INT";
    insert += ", ?";
  }
  create += ")";
  insert += ")";
  if (sqlite3_exec(db->get(), create.c_str(), nullptr, nullptr, nullptr) != SQLITE_OK ||
      sqlite3_exec(db->get(), "BEGIN", nullptr, nullptr, nullptr) != SQLITE_OK) {
    return make_error(std::string("SQLite: ") + sqlite3_errmsg(db->get()));
  }
  auto stmt = prepare(db->get(), insert);
  if (!stmt) return stmt.error();
  std::int64_t index = 0;
  for (const D6aRow& row : table.rows) {
    sqlite3_reset(stmt->get());
    sqlite3_bind_int64(stmt->get(), 1, ++index);
    sqlite3_bind_int(stmt->get(), 2, row.time_ms);
    for (std::size_t k = 0; k < table.servo_columns; ++k) {
      sqlite3_bind_int(stmt->get(), static_cast<int>(k + 3),
                       k < row.positions.size() ? row.positions[k] : 0);
    }
    if (sqlite3_step(stmt->get()) != SQLITE_DONE) {
      return make_error(std::string("SQLite: ") + sqlite3_errmsg(db->get()));
    }
  }
  if (sqlite3_exec(db->get(), "COMMIT", nullptr, nullptr, nullptr) != SQLITE_OK) {
    return make_error(std::string("SQLite: ") + sqlite3_errmsg(db->get()));
  }
  sqlite3_int64 size = 0;
  unsigned char* data = sqlite3_serialize(db->get(), "main", &size, 0);
  if (data == nullptr) return make_error("SQLite cannot serialize the database");
  std::string bytes(reinterpret_cast<const char*>(data), static_cast<std::size_t>(size));
  sqlite3_free(data);
  return bytes;
}

Result<D6aTable> d6a_from_program(const compiler::ServoProgram& program) {
  const compiler::RobotInfo& robot = program.robot;
  std::uint8_t last = robot.highest_defined_id;
  if (last == 0) {
    for (const compiler::ServoInfo& s : robot.servos) last = std::max(last, s.id);
  }
  D6aTable table;
  table.servo_columns = std::max<std::size_t>(6, last);
  std::vector<int> now(table.servo_columns, 500);
  for (const compiler::ServoInfo& s : robot.servos) {
    if (s.id >= 1 && s.id <= table.servo_columns) now[s.id - 1] = s.home;
  }
  for (const compiler::Keyframe& k : program.keyframes) {
    for (const lsc::ServoTarget& t : k.targets) {
      if (t.id == 0 || t.id > table.servo_columns) {
        return make_error("servo id " + std::to_string(t.id) + " has no column in a .d6a file " +
                          "(Servo1..Servo" + std::to_string(table.servo_columns) + ")");
      }
      now[t.id - 1] = t.position;
    }
    table.rows.push_back({static_cast<std::int64_t>(table.rows.size() + 1), k.time_ms, now});
  }
  return table;
}

std::string d6a_output_name(const std::string& path, int group) {
  if (path == "-") return "group" + std::to_string(group) + ".d6a";
  return std::filesystem::path(path).stem().string() + ".d6a";
}

}  // namespace seqc::compiler
