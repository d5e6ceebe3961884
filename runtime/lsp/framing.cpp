#include "runtime/lsp/framing.hpp"

#include <algorithm>
#include <cctype>
#include <string>

namespace seqc::lsp {
namespace {

constexpr std::string_view kLengthField = "content-length";
// Where a header block starts, looked for after a framing error to read on from the next
// message (a body seldom holds a newline, so the next header may follow it on the same line).
constexpr std::string_view kResyncMark = "Content-Length:";

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

}  // namespace

bool MessageReader::fill() {
  // Drop what was consumed before growing the buffer, so a long stream never piles up.
  if (pos_ > 0 && (pos_ >= buffer_.size() || pos_ > (64u << 10))) {
    buffer_.erase(0, pos_);
    pos_ = 0;
  }
  char chunk[16384];
  const std::size_t n = input_.read(chunk, sizeof chunk);
  if (n == 0) return false;
  buffer_.append(chunk, n);
  return true;
}

std::variant<std::string, FramingError, EndOfInput> MessageReader::header_line() {
  for (;;) {
    const std::size_t nl = buffer_.find('\n', pos_);
    if (nl != std::string::npos && nl - pos_ <= kMaxHeaderLine + 1) {
      std::string line = buffer_.substr(pos_, nl - pos_);
      pos_ = nl + 1;
      if (!line.empty() && line.back() == '\r') line.pop_back();
      return line;
    }
    if (buffer_.size() - pos_ > kMaxHeaderLine + 1) {
      return FramingError{"header line longer than " + std::to_string(kMaxHeaderLine) + " bytes"};
    }
    if (!fill()) return EndOfInput{};
  }
}

Frame MessageReader::next() {
  while (skip_ > 0) {  // the body of a message over the limit, dropped unread
    const std::size_t drop =
        static_cast<std::size_t>(std::min<std::uint64_t>(skip_, buffer_.size() - pos_));
    pos_ += drop;
    skip_ -= drop;
    if (skip_ > 0 && !fill()) return EndOfInput{};
  }
  if (resync_) {
    // Skip to the next "Content-Length:", keeping a tail that may be the start of one.
    for (;;) {
      const std::size_t at = buffer_.find(kResyncMark, pos_);
      if (at != std::string::npos) {
        pos_ = at;
        resync_ = false;
        break;
      }
      pos_ = std::max(pos_, buffer_.size() - std::min(buffer_.size(), kResyncMark.size() - 1));
      if (!fill()) return EndOfInput{};
    }
  }
  auto fail = [this](std::string why) {
    resync_ = true;
    return FramingError{std::move(why)};
  };
  std::optional<std::size_t> length;
  bool any_field = false;
  for (;;) {
    auto line = header_line();
    if (std::holds_alternative<EndOfInput>(line)) return EndOfInput{};
    if (auto* e = std::get_if<FramingError>(&line)) return fail(e->message);
    const std::string& text = std::get<std::string>(line);
    if (text.empty()) {
      if (!any_field) continue;  // a stray blank line between messages
      break;
    }
    any_field = true;
    const std::size_t colon = text.find(':');
    if (colon == std::string::npos) return fail("header line without a ':'");
    if (lower(trim(std::string_view(text).substr(0, colon))) != kLengthField) continue;
    const std::string_view value = trim(std::string_view(text).substr(colon + 1));
    if (value.empty() || value.size() > 12 || !std::all_of(value.begin(), value.end(), [](char c) {
          return std::isdigit(static_cast<unsigned char>(c));
        })) {
      return fail("Content-Length is not a number of bytes");
    }
    length = std::stoull(std::string(value));
  }
  if (!length) return fail("header without a Content-Length");
  if (*length > max_body_) {
    skip_ = *length;
    return FramingError{"message of " + std::to_string(*length) + " bytes is over the limit of " +
                        std::to_string(max_body_) + " bytes"};
  }
  while (buffer_.size() - pos_ < *length) {
    if (!fill()) return EndOfInput{};
  }
  FramedBody out{buffer_.substr(pos_, *length)};
  pos_ += *length;
  return out;
}

std::string frame(std::string_view body) {
  std::string out = "Content-Length: " + std::to_string(body.size()) + "\r\n\r\n";
  out.append(body);
  return out;
}

}  // namespace seqc::lsp
