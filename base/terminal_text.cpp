#include "base/terminal_text.hpp"

#include <cstdio>

#include "base/utf8.hpp"

namespace seqc {

std::string terminal_safe(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  char buf[8];
  for (std::size_t i = 0; i < text.size();) {
    const auto c = static_cast<unsigned char>(text[i]);
    const std::size_t n = utf8_length(text, i);
    if (n == 0) {
      std::snprintf(buf, sizeof buf, "\\x%02x", static_cast<unsigned>(c));
      out += buf;
      ++i;
    } else if (n == 2 && c == 0xC2 && static_cast<unsigned char>(text[i + 1]) < 0xA0) {
      std::snprintf(buf, sizeof buf, "\\u%04x", static_cast<unsigned char>(text[i + 1]) & 0xFFu);
      out += buf;
      i += 2;
    } else if (n > 1) {
      out.append(text.substr(i, n));
      i += n;
    } else {
      ++i;
      if (c == '\t' || (c >= 0x20 && c < 0x7F)) {
        out += static_cast<char>(c);
      } else if (c == '\n') {
        out += "\\n";
      } else if (c == '\r') {
        out += "\\r";
      } else {
        std::snprintf(buf, sizeof buf, "\\x%02x", static_cast<unsigned>(c));
        out += buf;
      }
    }
  }
  return out;
}

}  // namespace seqc
