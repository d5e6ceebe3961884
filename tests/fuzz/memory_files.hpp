// The fuzz targets' file system: the input is main.yaml, and "inc.yaml" is served as the same
// bytes (so self-inclusion and cycles are reachable); any other path does not exist. Nothing
// touches the disk.
#pragma once

#include <string>
#include <utility>

#include "base/source.hpp"

namespace seqc::fuzz {

class MemoryFiles final : public seqc::FileReader {
 public:
  explicit MemoryFiles(std::string text) : text_(std::move(text)) {}
  seqc::Result<std::string> read(const std::string& path) override {
    if (path == "main.yaml" || path == "inc.yaml") return text_;
    return seqc::make_error(path + ": No such file or directory");
  }

 private:
  std::string text_;
};

}  // namespace seqc::fuzz
