// The real file system behind seqc::FileReader.
#pragma once

#include "base/source.hpp"

namespace seqc::io {

class DiskFileReader final : public seqc::FileReader {
 public:
  // Files larger than max_bytes are refused unread, so a huge file cannot exhaust memory.
  explicit DiskFileReader(std::size_t max_bytes = 16u << 20) : max_bytes_(max_bytes) {}
  Result<std::string> read(const std::string& path) override;
  std::optional<std::uint64_t> size(const std::string& path) override;

 private:
  std::size_t max_bytes_;
};

// Writes `data` to `path` via a temporary file and rename, so a failed run never leaves a
// partial output behind.
Status write_file_atomically(const std::string& path, std::string_view data);

}  // namespace seqc::io
