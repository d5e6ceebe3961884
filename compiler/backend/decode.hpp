// `seqc decode`: servo-controller frames back into a readable action table, checking that a
// GroupDownload is internally consistent (order, block slots, counts, open/close).
#pragma once

#include <string>
#include <vector>

#include "runtime/protocol/bytes.hpp"

namespace seqc::backend {

struct DecodeResult {
  std::string table;                // the text `seqc decode` prints
  std::vector<std::string> issues;  // inconsistencies, also flagged inside the table
  std::size_t frames = 0;
  std::size_t actions = 0;
};

// Decodes any sequence of serial frames (whatever the line breaks), skipping and flagging
// garbage between frames.
DecodeResult decode_frames(ByteView bytes);

}  // namespace seqc::backend
