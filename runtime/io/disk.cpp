#include "runtime/io/disk.hpp"

#include <sys/stat.h>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>

namespace seqc::io {

Result<std::string> DiskFileReader::read(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) {
    return make_error(path + ": " + std::strerror(errno));
  }
  if (S_ISDIR(st.st_mode)) return make_error(path + ": is a directory");
  if (static_cast<std::size_t>(st.st_size) > max_bytes_) {
    return make_error(path + ": file is too large (" + std::to_string(st.st_size) +
                      " bytes; the limit is " + std::to_string(max_bytes_) + ")");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) return make_error(path + ": " + std::strerror(errno));
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::optional<std::uint64_t> DiskFileReader::size(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) return std::nullopt;
  return static_cast<std::uint64_t>(st.st_size);
}

Status write_file_atomically(const std::string& path, std::string_view data) {
  const std::string tmp = path + ".seqc-tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) return make_error(path + ": " + std::strerror(errno));
    out.write(data.data(), static_cast<std::streamsize>(data.size()));
    if (!out.flush()) {
      std::remove(tmp.c_str());
      return make_error(path + ": write failed");
    }
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    const std::string why = std::strerror(errno);
    std::remove(tmp.c_str());
    return make_error(path + ": " + why);
  }
  return Ok{};
}

}  // namespace seqc::io
