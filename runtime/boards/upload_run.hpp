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

// `--resync BARS`: the dance cut every `bars` bars (compiler::split_at_bars, times pre-scaled by
// `clock_ppm`), piece k for group first_group + k. Before any port opens.
struct ResyncCut {
  std::vector<compiler::ResyncPiece> pieces;
  std::string error;           // not empty: the dance cannot be cut there, and there are no pieces
  std::size_t last_group = 0;  // the last piece's group; above 254 the pieces do not fit
  bool fits() const { return error.empty() && last_group <= 254; }
};
ResyncCut cut_for_resync(const compiler::ServoProgram& program, std::uint32_t bars,
                         std::int32_t clock_ppm, std::uint8_t first_group);

}  // namespace seqc::boards
