// The real file system behind seqc::FileReader, and the one way seqc writes a file it was
// asked to write. seqc runs in hooks and CI on files other people prepared, so neither a read
// nor a write trusts what a path names: a read stops at a byte limit whatever the file is
// (a regular file, /dev/zero, a FIFO, a terminal), and a write never follows a link it did not
// ask for, never leaves a partial file behind and never turns a device into a regular file.
#pragma once

#include <chrono>
#include <cstddef>
#include <iosfwd>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "base/source.hpp"

namespace seqc::io {

// The most seqc reads from one input file or from standard input.
inline constexpr std::size_t kMaxInputBytes = 16u << 20;

class DiskFileReader final : public seqc::FileReader {
 public:
  // Files larger than max_bytes are refused: a regular file by its size, unread; anything else
  // (a device, a FIFO) after max_bytes + 1 bytes, so no file can exhaust memory or never end.
  // Nor can one make a read wait forever: a FIFO no process opens for writing within
  // writer_wait, or a device or pipe that gives nothing for idle_wait, is an error.
  explicit DiskFileReader(std::size_t max_bytes = kMaxInputBytes,
                          std::chrono::milliseconds writer_wait = std::chrono::milliseconds(500),
                          std::chrono::milliseconds idle_wait = std::chrono::seconds(10))
      : max_bytes_(max_bytes), writer_wait_(writer_wait), idle_wait_(idle_wait) {}
  Result<std::string> read(const std::string& path) override;
  std::optional<std::uint64_t> size(const std::string& path) override;

 private:
  std::size_t max_bytes_;
  std::chrono::milliseconds writer_wait_;
  std::chrono::milliseconds idle_wait_;
};

// Reads `in` to its end, or refuses once it has given more than max_bytes ("NAME: file is too
// large (more than N bytes)"); a stream error is an error too. name: what messages call it.
Result<std::string> read_stream(std::istream& in, const std::string& name,
                                std::size_t max_bytes = kMaxInputBytes);

// The text of the input a command was given: standard input `in` when `path` is "-" (read by
// read_stream(), which calls it `stdin_name`; "" when there is no stream), else the file at
// `path` through `files`. The error is the stream's or the reader's.
Result<std::string> read_input(const std::string& path, seqc::FileReader& files, std::istream* in,
                               const std::string& stdin_name);

// Writes `data` to `path`. A symlink is followed (to its end, as open() would) and the rules
// below apply to the file it names, which is the file replaced; the link itself stays.
//  - Absent or a regular file: the data goes to a temporary created exclusively (a random name,
//    O_CREAT|O_EXCL|O_NOFOLLOW, mode 0666 & ~umask) in the same folder, which is then renamed
//    over the file, so a failed run leaves the old file as it was and no temporary behind, and
//    nothing planted at a guessable name is ever opened.
//  - A character or block device, a FIFO or a socket (/dev/null, /dev/stdout, a named pipe):
//    opened and written directly, as cp and cc do; it stays what it is. So is a file reached
//    through /proc (/dev/stdout, /dev/fd/N when they name a file): it is some process's open
//    file, written where it is.
//  - Anything else (a directory): refused.
// Errors read "PATH: cannot write: WHY". Stop signals are held off while a temporary exists, so
// a signal that ends seqc at once leaves none behind.
Status write_file_safely(const std::string& path, std::string_view data);

// A file written as seqc runs (a --trace file), by the rules of write_file_safely: a regular or
// absent file is written to the exclusive temporary beside it and renamed over it by finish(); a
// device, a FIFO or a socket is written directly as the bytes come. Destroyed unfinished, the
// temporary is removed and the old file stays as it was.
class OutputFile {
 public:
  static Result<std::unique_ptr<OutputFile>> open(const std::string& path);
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;
  ~OutputFile();
  Status write(std::string_view data);
  // Closes the file and renames the temporary over the target; nothing may be written after.
  Status finish();

 private:
  OutputFile(std::string path, int fd, std::string temp, std::string target);
  std::string path_;    // as given, for messages
  std::string temp_;    // "" when written in place
  std::string target_;  // what the temporary replaces
  int fd_;
};

// Whether a and b are the same file: the same st_dev and st_ino, symlinks followed. False when
// either does not exist.
bool same_file(const std::string& a, const std::string& b);

// The first of `inputs` that `output` is the same file as, or "" when none is.
std::string same_file_among(const std::string& output, const std::vector<std::string>& inputs);

// `path` with "-" and `tag` before its extension, for one output file per part of a whole:
// "out.csv" and "arm" -> "out-arm.csv"; "out" -> "out-arm"; "runs.d/out" -> "runs.d/out-arm".
std::string tagged_path(const std::string& path, const std::string& tag);

}  // namespace seqc::io
