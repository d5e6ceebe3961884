// UTF-8 as RFC 3629 defines it, for the escapers that must tell a character from a stray byte
// (JSON, terminal and XML text): seqc quotes a hostile file's bytes, which need not be UTF-8.
#pragma once

#include <cstddef>
#include <string_view>

namespace seqc {

// The length of the valid UTF-8 sequence that starts at s[i] (1 for ASCII), or 0 when the bytes
// there are not one: overlong forms, surrogates, code points above U+10FFFF, a truncated
// sequence and a lone continuation byte are all invalid. i < s.size().
std::size_t utf8_length(std::string_view s, std::size_t i);

}  // namespace seqc
