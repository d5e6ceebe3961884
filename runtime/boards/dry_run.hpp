// What an upload would send, without a board: the board's own upload function runs against an
// AcknowledgingTransport, so the frames listed are the frames an upload writes, in its order,
// and cannot drift from it. The text has one line per frame: its hex, then the board's comment.
#pragma once

#include <string>
#include <vector>

#include "runtime/boards/board.hpp"
#include "base/bytes.hpp"
#include "runtime/upload/uploader.hpp"

namespace seqc::boards {

struct DryRun {
  upload::UploadResult result;  // Completed unless the plan is bad (the CLI says Internal)
  std::vector<Bytes> frames;    // every write, in order: exactly what an upload sends
  std::string text;  // one line per frame: fmt "{:<40}  # {}\n" (hex, Board::comment(i, frame))
};

// `board` must have storage (plan, upload, acknowledge and comment).
DryRun dry_run(const Board& board, const Plan& plan, const upload::UploadOptions& options);

}  // namespace seqc::boards
