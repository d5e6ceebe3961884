// Test helpers: hand-written hex literals to bytes, and bytes back to hex for readable failures.
#pragma once

#include <gtest/gtest.h>

#include <string>
#include <string_view>

#include "base/bytes.hpp"
#include "base/result.hpp"

namespace seqc::test {

// Bytes from a hand-written hex literal; a malformed literal fails the test.
inline Bytes hex(std::string_view text) {
  auto bytes = parse_hex(text);
  EXPECT_TRUE(bytes.ok()) << "bad hex literal in test: " << text;
  return bytes.ok() ? *bytes : Bytes{};
}

// Canonical lowercase form of a hand-written literal, for EXPECT_EQ on hex strings.
inline std::string norm(std::string_view text) { return to_hex(hex(text)); }

// The hex of an encoder result, or "error: ..." so a failure shows the message.
inline std::string hex_or_error(const Result<Bytes>& bytes) {
  return bytes.ok() ? to_hex(*bytes) : "error: " + bytes.error().message;
}

}  // namespace seqc::test
