// Hiwonder's .d6a action files: a SQLite database with one table,
//   ActionGroup([Index] INTEGER PRIMARY KEY AUTOINCREMENT, Time INT, Servo1 INT, ..., ServoN INT)
// one row per controller action, Time in ms, ServoK the position of bus servo id K (0-1000),
// every servo in every row. The file goes through SQLite itself (libsqlite3, in memory: the
// bytes come in and go out through the caller, so this stays free of I/O), never a hand-written
// reader. See docs/d6a.md.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "base/result.hpp"
#include "compiler/program/program.hpp"

namespace seqc::compiler {

struct D6aRow {
  std::int64_t index = 0;      // [Index], as stored
  int time_ms = 0;             // Time
  std::vector<int> positions;  // positions[k - 1] is ServoK
};

struct D6aTable {
  std::size_t servo_columns = 0;  // Servo1..ServoN
  std::vector<D6aRow> rows;       // in [Index] order
  friend bool operator==(const D6aTable&, const D6aTable&) = default;
};

// What reading one .d6a file may cost. The file is hostile until read: a few KB can hold a view
// whose rows never end, or a trigger, so the database is read only, never on disk (temporary
// tables and sorts stay in memory), views and triggers are refused before any query runs, and
// SQLite is interrupted past a budget of virtual-machine steps.
struct D6aReadLimits {
  std::size_t max_rows = 65536;          // a controller holds 1,020 actions
  std::uint64_t max_steps = 50'000'000;  // SQLite VM instructions (checked every thousand)
};

// Reads a .d6a file's bytes. A file that is not SQLite, or has no ActionGroup table, or lacks
// its Time or ServoK columns, or holds a value that is not a whole number, or holds a view,
// trigger or virtual table, or is past a limit, is an error naming what is wrong.
Result<D6aTable> read_d6a(std::string_view bytes, const D6aReadLimits& limits = {});

// The bytes of a .d6a file holding `table` ([Index] 1..n in row order).
Result<std::string> write_d6a(const D6aTable& table);

// The compiled actions of `program` as a table: one row per action, its time, and every servo
// id 1..columns at its position at the end of that action (home until something moves it).
// columns: the highest id the file's robot section names, else the profile's highest id, and
// at least 6. A servo with id 0 (an LSC channel 0) has no column: that is an error.
Result<D6aTable> d6a_from_program(const compiler::ServoProgram& program);

// Where a choreography at `path` is exported when no output is named: its stem with .d6a, in
// the current folder; for "-" (standard input), which has no name, groupN.d6a.
std::string d6a_output_name(const std::string& path, int group);

}  // namespace seqc::compiler
