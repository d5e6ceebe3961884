#include "base/source.hpp"

#include <utility>

namespace seqc {

namespace {
// Out-of-range file indexes quote nothing rather than crash: a diagnostic with a stale index
// must still render.
const std::string kEmpty;
}  // namespace

std::uint32_t SourceManager::add(std::string path, std::string text) {
  File f{std::move(path), std::move(text), {0}, true};
  for (std::size_t i = 0; i < f.text.size(); ++i) {
    if (f.text[i] == '\n') f.line_starts.push_back(i + 1);
  }
  files_.push_back(std::move(f));
  return static_cast<std::uint32_t>(files_.size() - 1);
}

const std::string& SourceManager::path(std::uint32_t file) const {
  return file < files_.size() ? files_[file].path : kEmpty;
}

const std::string& SourceManager::text(std::uint32_t file) const {
  return file < files_.size() ? files_[file].text : kEmpty;
}

std::size_t SourceManager::line_count(std::uint32_t file) const {
  return file < files_.size() ? files_[file].line_starts.size() : 0;
}

bool SourceManager::quotes_lines(std::uint32_t file) const {
  return file < files_.size() && files_[file].quoted;
}

void SourceManager::withhold_lines(std::uint32_t file) {
  if (file < files_.size()) files_[file].quoted = false;
}

std::string_view SourceManager::line(std::uint32_t file, std::uint32_t line) const {
  if (file >= files_.size() || line == 0) return {};
  const File& f = files_[file];
  if (line > f.line_starts.size()) return {};
  const std::size_t begin = f.line_starts[line - 1];
  // A file ending in '\n' has no extra empty last line worth quoting, but asking for it is
  // harmless: it is empty.
  std::size_t end = line < f.line_starts.size() ? f.line_starts[line] - 1 : f.text.size();
  if (end > begin && f.text[end - 1] == '\r') --end;  // CRLF files quote cleanly
  return std::string_view(f.text).substr(begin, end - begin);
}

}  // namespace seqc
