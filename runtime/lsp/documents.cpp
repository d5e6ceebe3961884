#include "runtime/lsp/documents.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <utility>

namespace seqc::lsp {
namespace {

// The bytes of the UTF-8 character that starts with `lead` (1 for an invalid lead byte).
std::size_t char_bytes(unsigned char lead) {
  if (lead >= 0xF0 && lead <= 0xF7) return 4;
  if (lead >= 0xE0) return lead <= 0xEF ? 3 : 1;
  if (lead >= 0xC2 && lead <= 0xDF) return 2;
  return 1;
}

// How many bytes the character at `i` spans, trusting its lead byte only when the following
// bytes are continuation bytes within the text.
std::size_t step(std::string_view text, std::size_t i) {
  const std::size_t n = char_bytes(static_cast<unsigned char>(text[i]));
  if (i + n > text.size()) return 1;
  for (std::size_t k = 1; k < n; ++k) {
    if ((static_cast<unsigned char>(text[i + k]) & 0xC0) != 0x80) return 1;
  }
  return n;
}

int hex_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

}  // namespace

std::uint32_t utf16_length(std::string_view bytes) {
  std::uint32_t units = 0;
  for (std::size_t i = 0; i < bytes.size();) {
    const std::size_t n = step(bytes, i);
    units += n == 4 ? 2 : 1;
    i += n;
  }
  return units;
}

std::size_t offset_of(std::string_view text, Position at) {
  std::size_t start = 0;
  for (std::uint32_t line = 0; line < at.line; ++line) {
    const std::size_t nl = text.find('\n', start);
    if (nl == std::string_view::npos) return text.size();
    start = nl + 1;
  }
  std::size_t end = text.find('\n', start);
  if (end == std::string_view::npos) end = text.size();
  if (end > start && text[end - 1] == '\r') --end;  // "\r\n" ends the line before the '\r'
  std::size_t i = start;
  std::uint32_t units = 0;
  while (i < end && units < at.character) {
    const std::size_t n = step(text, i);
    units += n == 4 ? 2 : 1;
    i += n;
  }
  return std::min(i, end);
}

void apply_edit(std::string& text, Position start, Position end, std::string_view replacement) {
  std::size_t from = offset_of(text, start);
  std::size_t to = offset_of(text, end);
  if (from > to) std::swap(from, to);
  text.replace(from, to - from, replacement);
}

std::string uri_to_path(std::string_view uri) {
  constexpr std::string_view kScheme = "file://";
  if (!uri.starts_with(kScheme)) return std::string(uri);
  std::string_view rest = uri.substr(kScheme.size());
  // file://host/path: the path starts at the first '/' ("localhost" and "" are this machine).
  const std::size_t slash = rest.find('/');
  rest = slash == std::string_view::npos ? std::string_view() : rest.substr(slash);
  std::string out;
  for (std::size_t i = 0; i < rest.size(); ++i) {
    if (rest[i] == '%' && i + 2 < rest.size()) {
      const int hi = hex_value(rest[i + 1]);
      const int lo = hex_value(rest[i + 2]);
      if (hi >= 0 && lo >= 0) {
        out += static_cast<char>(hi * 16 + lo);
        i += 2;
        continue;
      }
    }
    out += rest[i];
  }
  return out;
}

std::string path_to_uri(std::string_view path) {
  if (!path.starts_with("/")) return std::string(path);  // an untitled buffer's own name
  std::string out = "file://";
  for (unsigned char c : path) {
    if (std::isalnum(c) || c == '-' || c == '.' || c == '_' || c == '~' || c == '/') {
      out += static_cast<char>(c);
    } else {
      char buf[4];
      std::snprintf(buf, sizeof buf, "%%%02X", c);
      out += buf;
    }
  }
  return out;
}

std::string normal_path(std::string_view path) {
  if (path.empty()) return std::string();
  return std::filesystem::path(path).lexically_normal().string();
}

Result<std::string> OverlayReader::read(const std::string& path) {
  if (auto it = open_.find(normal_path(path)); it != open_.end()) return *it->second;
  return rest_.read(path);
}

std::optional<std::uint64_t> OverlayReader::size(const std::string& path) {
  if (auto it = open_.find(normal_path(path)); it != open_.end()) return it->second->size();
  return rest_.size(path);
}

}  // namespace seqc::lsp
