// `seqc decode`: servo-controller frames back into a readable action table, checking that a
// GroupDownload is internally consistent (order, block slots, counts, open/close).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "base/bytes.hpp"
#include "protocol/lsc/lsc_frame.hpp"

namespace seqc::compiler {

struct DecodeResult {
  std::string table;                // the text `seqc decode` prints
  std::vector<std::string> issues;  // inconsistencies, also flagged inside the table
  std::size_t frames = 0;
  std::size_t actions = 0;
};

// Decodes any sequence of serial frames (whatever the line breaks), skipping and flagging
// garbage between frames.
DecodeResult decode_frames(ByteView bytes);

// The frame walk both dialects' decoders share: `on_frame` for each frame in order (after
// `frames` counts it), `issue` for bytes outside frames and for input that ends inside one.
void walk_frames(ByteView bytes, std::size_t& frames,
                 const std::function<void(const lsc::Frame&)>& on_frame,
                 const std::function<void(std::string)>& issue);

}  // namespace seqc::compiler
