// What the Raspblock language tests share: a car file's stream as one "at_ms: hex" line per
// frame, and the stop frame every stream ends with.
#pragma once

#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "compiler/targets/raspblock/raspblock_stream.hpp"
#include "base/bytes.hpp"
#include "tests/compiler/lang_test_util.hpp"

namespace seqc::compiler::testing {

// "at_ms: hex" per frame of the stream `text` compiles to (a test failure if it does not).
inline std::vector<std::string> frames_of(const std::string& text) {
  auto out = compile_text(text);
  const RaspblockProgram* p = out.raspblock_program();
  EXPECT_NE(p, nullptr) << diagnostics_of(out);
  if (p == nullptr) return {};
  auto frames = compiler::plan_stream(*p);
  EXPECT_TRUE(frames.ok());
  std::vector<std::string> lines;
  for (const auto& f : *frames) lines.push_back(std::to_string(f.at_ms) + ": " + to_hex(f.bytes));
  return lines;
}

// Rocker 0,0,0: data 01 00 00 00 00 00 00 01 (Z = 0 sets the Z bit); 03+08+01+01 = 0d.
inline const std::string kStop = "ff fe 03 08 01 00 00 00 00 00 00 01 0d";

}  // namespace seqc::compiler::testing
