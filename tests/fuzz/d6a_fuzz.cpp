// Fuzz target: a .d6a file's bytes through read_d6a, as `seqc import` reads a file a stranger
// handed over. Invariants: no crash, hang or sanitizer report; a table read is within the row
// limit, every row has a position for every servo column, rows come in [Index] order; and a
// table read is written and read back unchanged.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "compiler/formats/d6a.hpp"
#include "tests/fuzz/fuzz_check.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  // A small budget: the fuzzer's inputs are small, and a slow one should show as a slow input.
  seqc::compiler::D6aReadLimits limits;
  limits.max_rows = 2000;
  limits.max_steps = 2'000'000;
  const auto table = seqc::compiler::read_d6a(bytes, limits);
  if (!table) {
    FUZZ_CHECK(!table.error().message.empty());
    return 0;
  }
  FUZZ_CHECK(table->rows.size() <= limits.max_rows);
  for (std::size_t i = 0; i < table->rows.size(); ++i) {
    FUZZ_CHECK(table->rows[i].positions.size() == table->servo_columns);
    if (i > 0) FUZZ_CHECK(table->rows[i - 1].index <= table->rows[i].index);
  }
  const auto written = seqc::compiler::write_d6a(*table);
  if (!written) return 0;  // e.g. no rows, or more columns than a file holds
  const auto again = seqc::compiler::read_d6a(*written, limits);
  FUZZ_CHECK(again.ok());
  FUZZ_CHECK(again->servo_columns == table->servo_columns);
  FUZZ_CHECK(again->rows.size() == table->rows.size());
  for (std::size_t i = 0; i < table->rows.size(); ++i) {
    FUZZ_CHECK(again->rows[i].time_ms == table->rows[i].time_ms);
    FUZZ_CHECK(again->rows[i].positions == table->rows[i].positions);
  }
  return 0;
}
