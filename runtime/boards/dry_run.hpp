// What an upload would send, without a board: the board's own upload function runs against an
// AcknowledgingTransport, so the frames listed are the frames an upload writes, in its order,
// and cannot drift from it. The text has one line per frame: its hex, then the board's comment.
#pragma once

#include <string>
#include <vector>

#include "base/bytes.hpp"
#include "runtime/boards/board.hpp"
#include "runtime/upload/uploader.hpp"

namespace seqc::boards {

struct DryRun {
  upload::UploadResult result;  // Completed unless the plan is bad (the CLI says Internal)
  std::vector<Bytes> frames;    // every write, in order: exactly what an upload sends
  std::string text;  // one line per frame: fmt "{:<40}  # {}\n" (hex, Board::comment(i, frame))
};

// `board` must have storage (plan, upload, acknowledge and comment).
DryRun dry_run(const Board& board, const Plan& plan, const upload::UploadOptions& options);

// What `seqc compile` writes for `output`: the board's rendering in `emit`, or with `dry_run` on
// a board that stores groups, the frames its upload into `group` would send (dry_run). A board
// without storage has nothing to upload: its program is listed as `emit` lists it. On failure
// `error` says why (the file cannot be rendered or planned), or the dry run itself failed
// (`internal`, a bug rather than bad input).
struct CompiledText {
  std::string text;
  std::string error;  // not empty: nothing to write
  bool internal = false;
};
CompiledText compiled_text(const compiler::CompileOutput& output, std::uint8_t group, bool dry_run,
                           Emit emit);

}  // namespace seqc::boards
