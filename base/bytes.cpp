#include "base/bytes.hpp"

#include <cctype>

namespace seqc {

std::string to_hex(ByteView bytes) {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string out;
  out.reserve(bytes.size() * 3);
  for (std::size_t i = 0; i < bytes.size(); ++i) {
    if (i != 0) out.push_back(' ');
    out.push_back(kDigits[bytes[i] >> 4]);
    out.push_back(kDigits[bytes[i] & 0x0f]);
  }
  return out;
}

namespace {
int hex_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}
}  // namespace

Result<Bytes> parse_hex(std::string_view text) {
  Bytes out;
  std::size_t i = 0;
  while (i < text.size()) {
    if (std::isspace(static_cast<unsigned char>(text[i]))) {
      ++i;
      continue;
    }
    std::size_t start = i;
    while (i < text.size() && !std::isspace(static_cast<unsigned char>(text[i]))) ++i;
    std::string_view token = text.substr(start, i - start);
    if (token.size() > 2 && token[0] == '0' && (token[1] == 'x' || token[1] == 'X')) {
      token.remove_prefix(2);
    }
    if (token.size() != 2 || hex_value(token[0]) < 0 || hex_value(token[1]) < 0) {
      // A binary file has "tokens" of any length: quote the start of it.
      const std::string_view bad = text.substr(start, i - start);
      return make_error(
          "not a hex byte: '" +
          (bad.size() > 40 ? std::string(bad.substr(0, 40)) + "..." : std::string(bad)) + "'");
    }
    out.push_back(static_cast<std::uint8_t>(hex_value(token[0]) * 16 + hex_value(token[1])));
  }
  return out;
}

}  // namespace seqc
