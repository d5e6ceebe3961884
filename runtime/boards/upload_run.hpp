// `seqc upload`'s choices apart from its words (cli/cmd_upload.cpp words them): the uploader's
// options for what was asked, the pieces of a `--resync` run and whether their groups fit, and
// the first-move guard of a run. The robot may be anywhere when a group starts, so where the
// board reads its servos (first_move.hpp) a run whose first move is too fast from there is not
// started unless forced: when the uploader sends the run, the check is its may_run, so the group
// is stored but not started; with --music the computer starts it on the downbeat, and checks
// first (first_move.hpp's run_too_fast). Returns data only.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "compiler/compile.hpp"
#include "compiler/targets/servo_controller/chain.hpp"
#include "compiler/targets/servo_controller/resync.hpp"
#include "runtime/boards/board.hpp"
#include "runtime/boards/first_move.hpp"
#include "runtime/upload/uploader.hpp"

namespace seqc::boards {

// What `seqc upload` was asked, as plain values.
struct UploadRequest {
  std::uint8_t group = 0;
  int retries = 4;
  bool run = false;         // start the group once it is stored
  std::uint16_t times = 1;  // with run: 0 plays it until stopped
  bool force = false;       // start even when a first move is too fast
  bool music = false;       // the run is sent on the song's downbeat, after the upload
  bool dry_run = false;     // nothing is sent: the run is shown where it would be sent
};

// The uploader's options for `request`: the run is the uploader's unless it waits for the
// downbeat (a dry run still shows it), and where it is the uploader's and not forced, it is asked
// for through may_run, which reads the servos over the upload's own line and leaves the finding
// that refused it in `too_fast` (which must outlive the options).
upload::UploadOptions upload_options(const UploadRequest& request, const Board& board,
                                     const compiler::CompileOutput& output,
                                     const std::atomic<bool>* interrupted,
                                     std::optional<FirstMoveTooFast>& too_fast);

// The pieces of a run the computer starts one by one, before any port opens: `--resync BARS`
// cuts the dance every `bars` bars (compiler::split_at_bars); a dance over one group's capacity
// without it is cut into the fewest groups, each starting exactly on a bar line
// (compiler::chain_groups). Times pre-scaled by `clock_ppm`; piece k for group first_group + k.
struct ResyncCut {
  std::vector<compiler::ResyncPiece> pieces;
  std::vector<std::int64_t> bars;  // chained: the bar each piece starts on (0: none)
  std::string error;               // not empty: it cannot be cut so (worded), and no pieces
  std::size_t last_group = 0;      // the last piece's group
  bool chained = false;            // cut for the capacity, not every BARS bars
  bool fits() const { return error.empty(); }
};
// bars 0: the chain (only for a dance longer than one group).
ResyncCut cut_for_resync(const compiler::ServoProgram& program, std::uint32_t bars,
                         std::int32_t clock_ppm, std::uint8_t first_group);

// "4 pieces of 8 bars", or chained "3 groups starting on bars 1, 129 and 257" (bars: --resync's).
std::string pieces_text(const ResyncCut& cut, std::uint32_t bars);

// Whether `program` needs more than one group.
bool needs_chain(const compiler::ServoProgram& program);

}  // namespace seqc::boards
