// A plain text table for device readings: left-aligned columns two spaces apart, a header row,
// no trailing spaces. Numbers are right-aligned so columns of values line up.
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
