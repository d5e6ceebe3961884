// The documents a client has open, as LSP describes them: file:// URIs, positions in UTF-16
// code units, and edits that replace a range (incremental sync) or the whole text.
//
// The compiler counts columns in bytes of UTF-8 and reads files through a FileReader; this
// file converts between the two ways of counting and serves an open document's unsaved text
// in place of the file on disk (OverlayReader), so a file that includes an open one sees what
// is typed in it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "base/source.hpp"

namespace seqc::lsp {

// An LSP position: a 0-based line and a character counted in UTF-16 code units.
struct Position {
  std::uint32_t line = 0;
  std::uint32_t character = 0;
  friend bool operator==(const Position&, const Position&) = default;
};

// The byte offset in `text` of `at`. A line past the end is the end of the text; a character
// past the end of its line is the end of that line (the protocol's rule); a character inside
// a surrogate pair (the middle of a 4-byte character) is the end of that character. Bytes that
// are no valid UTF-8 count one unit each.
std::size_t offset_of(std::string_view text, Position at);

// The UTF-16 code units of `bytes` (UTF-8; an invalid byte counts as one unit).
std::uint32_t utf16_length(std::string_view bytes);

// `text` with the range [start, end) replaced by `replacement` (start after end: swapped).
void apply_edit(std::string& text, Position start, Position end, std::string_view replacement);

// file:// URI <-> path. A URI that is no file:// URI is its own "path" (an untitled buffer),
// so it can still be compiled from its open text.
std::string uri_to_path(std::string_view uri);
std::string path_to_uri(std::string_view path);

// `path` with "." and ".." resolved lexically, the key under which an open document is found.
std::string normal_path(std::string_view path);

// Open documents' texts by normal path, shared so a snapshot is cheap to take and to hand to
// another thread.
using DocumentTexts = std::map<std::string, std::shared_ptr<const std::string>>;

// A FileReader serving open documents' texts (a snapshot) over the reader underneath (the disk).
class OverlayReader final : public FileReader {
 public:
  OverlayReader(DocumentTexts open, FileReader& rest) : open_(std::move(open)), rest_(rest) {}
  Result<std::string> read(const std::string& path) override;
  std::optional<std::uint64_t> size(const std::string& path) override;

 private:
  DocumentTexts open_;
  FileReader& rest_;
};

}  // namespace seqc::lsp
