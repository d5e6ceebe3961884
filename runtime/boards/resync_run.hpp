// `seqc upload --resync BARS --run`: a dance cut into pieces at bar lines
// (compiler/targets/servo_controller/resync.hpp), piece k stored in group first_group + k through
// the board's own uploader, then every piece started by the computer on the line's clock at its
// host time (runtime/player: absolute deadlines). Each start is the board's stop frame followed by
// its run frame in one write, so a piece still playing on a slow clock is cut short rather than the
// next start ignored (the LSC-6 ignores a run of another group while one plays). With `--music`
// the song's downbeat as heard is the first start, and the rest follow on the same clock. Returns
// data only.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "compiler/compile.hpp"
#include "compiler/targets/servo_controller/resync.hpp"
#include "runtime/boards/board.hpp"
#include "runtime/boards/music_session.hpp"
#include "runtime/player/player.hpp"
#include "runtime/upload/uploader.hpp"

namespace seqc::boards {

struct ResyncRun {
  std::vector<upload::UploadResult> uploads;  // one per piece tried, in order
  bool stored() const { return !uploads.empty() && uploads.back().ok(); }
  std::vector<player::ScheduledFrame> starts;  // what was (or would have been) sent, and when
  player::PlayReport play;                     // set when every piece was stored
  bool run_refused = false;  // options.may_run said no after storing: nothing was started
  std::string song_error;    // with a song: the output refused to start it; nothing was started
  // How late the latest start was written (0 before any start).
  io::Duration latest_start() const;
};

// The starts of `pieces` (groups first_group, first_group + 1, ...) as a schedule.
std::vector<player::ScheduledFrame> resync_starts(const Board& board,
                                                  const std::vector<compiler::ResyncPiece>& pieces,
                                                  std::uint8_t first_group);

// One piece's group as the board stores it (the dance's robot, the piece's actions).
Result<Plan> plan_for_piece(const Board& board, const compiler::CompileOutput& output,
                            const compiler::ResyncPiece& piece, std::uint8_t group);

// Requires board.plan, board.upload, board.run_frame. `output` is the compiled dance (its robot
// is kept for every piece). Stops at the first piece that does not store.
ResyncRun store_pieces(const Board& board, const Line& line, const compiler::CompileOutput& output,
                       const std::vector<compiler::ResyncPiece>& pieces, std::uint8_t first_group,
                       const upload::UploadOptions& options, upload::UploadObserver* observer);

// Once r.stored() (else nothing): options.may_run (if set) is asked before the first start, as
// an upload asks it before its run, then every piece is started at its time. Apart from the
// storing, so a caller can keep time (`--realtime`) over the starts alone.
//
// With `music` (open, not started: `--music`), once may_run agrees the song is started
// (start_music; its refusal in r.song_error, and nothing is started) and the first start
// finishes arriving, plus the board's start delay, on the song's downbeat as heard
// (live_song_start; `host` is the clock the song is dated on); every later start is on the same
// clock, its bar line's time after that, each written its own wire time early. Returns the first
// start's timing against the song (for the report); nullopt without a song or when nothing was
// started.
std::optional<SyncedStart> start_pieces(const Board& board, const Line& line,
                                        const std::vector<compiler::ResyncPiece>& pieces,
                                        std::uint8_t first_group,
                                        const upload::UploadOptions& options, ResyncRun& r,
                                        MusicSession* music = nullptr, io::Clock* host = nullptr);

// store_pieces, then start_pieces.
ResyncRun store_and_start(const Board& board, const Line& line,
                          const compiler::CompileOutput& output,
                          const std::vector<compiler::ResyncPiece>& pieces,
                          std::uint8_t first_group, const upload::UploadOptions& options,
                          upload::UploadObserver* observer);

}  // namespace seqc::boards
