// A plain text table for device readings: a header row, left-aligned columns two spaces apart,
// no trailing spaces.
#pragma once

#include <string>
#include <vector>

namespace seqc::cli {

class Table {
 public:
  explicit Table(std::vector<std::string> header) : rows_{std::move(header)} {}
  void add(std::vector<std::string> row) { rows_.push_back(std::move(row)); }
  std::string render() const;

 private:
  std::vector<std::vector<std::string>> rows_;
};

}  // namespace seqc::cli
