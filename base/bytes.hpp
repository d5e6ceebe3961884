// Byte buffers and the hex text form used in dumps, golden files and `seqc decode`.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "base/result.hpp"

namespace seqc {

using Bytes = std::vector<std::uint8_t>;
using ByteView = std::span<const std::uint8_t>;

// Lowercase two-digit hex bytes separated by single spaces: "55 55 02 0f".
std::string to_hex(ByteView bytes);

// Parses hex bytes separated by white space (either case, "0x" prefixes allowed).
Result<Bytes> parse_hex(std::string_view text);

}  // namespace seqc
