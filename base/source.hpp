// Source files, locations, and the file-system boundary of the compiler.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "base/result.hpp"

namespace seqc {

// 1-based line and column (columns count bytes, as clang does). file is an index into
// SourceManager; line 0 means "no location" (e.g. a command-line option).
struct Location {
  std::uint32_t file = 0;
  std::uint32_t line = 0;
  std::uint32_t column = 0;
  friend bool operator==(const Location&, const Location&) = default;
};

// A Location whose file is kNoFile belongs to no file at all: it renders as "seqc: error: ...".
inline constexpr std::uint32_t kNoFile = 0xFFFFFFFFu;

// The compiler's only access to the file system (see docs/architecture.md). Paths are as the user
// wrote them, resolved by the caller; the reader returns the whole file's bytes.
class FileReader {
 public:
  virtual ~FileReader() = default;
  virtual Result<std::string> read(const std::string& path) = 0;
  // The file's size without reading it, where the reader can tell (so a file far over the
  // loader's limit is refused unread); nullopt otherwise.
  virtual std::optional<std::uint64_t> size(const std::string& /*path*/) { return std::nullopt; }
};

// A song's audio, decoded to mono samples (channels averaged, in [-1, 1]).
struct SongSamples {
  std::vector<float> samples;
  double sample_rate = 0;
};

// The compiler's only access to audio: the song of a `music:` block, decoded by the caller
// (libsndfile in the CLI, generated samples in tests). Paths are resolved as for FileReader.
class SongReader {
 public:
  virtual ~SongReader() = default;
  // The whole song, or an Error naming the path and what is wrong with it.
  virtual Result<SongSamples> read(const std::string& path) = 0;
  // The song encoded small enough to embed in a page (Ogg Vorbis, mono), for a file too large
  // to embed as it is; an Error saying why not. None by default: a reader that only decodes.
  virtual Result<std::string> compressed(const std::string& path) {
    return make_error(path + ": no encoder was given to make a smaller copy");
  }
};

// Owns the text of every file read in one compilation so diagnostics can quote source lines.
class SourceManager {
 public:
  std::uint32_t add(std::string path, std::string text);
  const std::string& path(std::uint32_t file) const;
  const std::string& text(std::uint32_t file) const;
  // The text of a 1-based line without its newline (empty if out of range).
  std::string_view line(std::uint32_t file, std::uint32_t line) const;
  std::size_t file_count() const { return files_.size(); }
  // Lines in the file (a final '\n' starts one more, empty, line); 0 for an unknown file.
  std::size_t line_count(std::uint32_t file) const;
  // Whether diagnostics may quote the file's lines: true unless withheld. An include that did not
  // parse as a choreography file may be any file the user can read (`include: /etc/shadow`), so
  // its problems are located but none of its lines is copied into a message or a report.
  bool quotes_lines(std::uint32_t file) const;
  void withhold_lines(std::uint32_t file);

 private:
  struct File {
    std::string path;
    std::string text;
    std::vector<std::size_t> line_starts;
    bool quoted = true;
  };
  std::vector<File> files_;
};

}  // namespace seqc
