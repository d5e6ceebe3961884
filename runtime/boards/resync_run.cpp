#include "runtime/boards/resync_run.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace seqc::boards {

io::Duration ResyncRun::latest_start() const {
  io::Duration latest{0};
  for (const io::Duration& l : play.lateness) latest = std::max(latest, l);
  return latest;
}

std::vector<player::ScheduledFrame> resync_starts(const Board& board,
                                                  const std::vector<compiler::ResyncPiece>& pieces,
                                                  std::uint8_t first_group) {
  std::vector<player::ScheduledFrame> out;
  for (std::size_t k = 0; k < pieces.size(); ++k) {
    const auto group = static_cast<std::uint8_t>(first_group + k);
    Bytes bytes = board.stop_frame != nullptr ? board.stop_frame() : Bytes{};
    const Bytes run = board.run_frame(group, 1);
    bytes.insert(bytes.end(), run.begin(), run.end());
    const auto ns = static_cast<std::int64_t>(std::llround(pieces[k].host_start.value() * 1e6));
    out.push_back({io::Duration{ns}, std::move(bytes)});
  }
  return out;
}

Result<Plan> plan_for_piece(const Board& board, const compiler::CompileOutput& output,
                            const compiler::ResyncPiece& piece, std::uint8_t group) {
  compiler::CompileOutput one;
  compiler::ServoProgram program;
  if (const compiler::ServoProgram* dance = output.servo_program()) program.robot = dance->robot;
  program.keyframes = piece.keyframes;
  one.program = std::move(program);
  one.board = output.board;
  return plan_for(board, one, group);
}

ResyncRun store_pieces(const Board& board, const Line& line, const compiler::CompileOutput& output,
                       const std::vector<compiler::ResyncPiece>& pieces, std::uint8_t first_group,
                       const upload::UploadOptions& options, upload::UploadObserver* observer) {
  ResyncRun r;
  const compiler::ServoProgram* dance = output.servo_program();
  if (dance == nullptr) return r;
  for (std::size_t k = 0; k < pieces.size(); ++k) {
    const auto group = static_cast<std::uint8_t>(first_group + k);
    auto plan = plan_for_piece(board, output, pieces[k], group);
    if (!plan) {
      upload::UploadResult failed;
      failed.status = upload::UploadStatus::BadPlan;
      failed.message = plan.error().message;
      r.uploads.push_back(std::move(failed));
      return r;
    }
    upload::UploadOptions piece_options = options;
    piece_options.group = group;
    piece_options.run = false;
    r.uploads.push_back(upload(board, line, *plan, piece_options, observer));
    if (!r.uploads.back().ok()) return r;
  }
  return r;
}

std::optional<SyncedStart> start_pieces(const Board& board, const Line& line,
                                        const std::vector<compiler::ResyncPiece>& pieces,
                                        std::uint8_t first_group,
                                        const upload::UploadOptions& options, ResyncRun& r,
                                        MusicSession* music, io::Clock* host) {
  if (!r.stored()) return std::nullopt;
  r.starts = resync_starts(board, pieces, first_group);
  if (options.may_run && !options.may_run(line.transport, line.clock)) {
    r.run_refused = true;
    return std::nullopt;
  }
  player::PlayOptions play;
  play.interrupted = line.interrupted;
  if (board.stop_frame != nullptr) play.safe_stop = board.stop_frame();
  std::optional<LiveSongStart> song;
  if (music != nullptr) {
    if (Status started = start_music(*music); !started) {
      r.song_error = started.error().message;
      return std::nullopt;
    }
    // The first start (stop + run in one write) is timed whole, as a live play's first frame.
    const double per_byte = line.transport.seconds_per_byte();
    song = live_song_start(board, *music, r.starts.front().bytes.size(), per_byte,
                           host != nullptr ? *host : line.clock, line.clock);
    play.start_at = song->start.at;
    play.early = song->start.early;
    play.seconds_per_byte = per_byte;
  }
  r.play = player::play(r.starts, line.transport, line.clock, play);
  if (!song) return std::nullopt;
  return synced_start(song->plan, song->wire, song->start.early, first_written(r.play));
}

ResyncRun store_and_start(const Board& board, const Line& line,
                          const compiler::CompileOutput& output,
                          const std::vector<compiler::ResyncPiece>& pieces,
                          std::uint8_t first_group, const upload::UploadOptions& options,
                          upload::UploadObserver* observer) {
  ResyncRun r = store_pieces(board, line, output, pieces, first_group, options, observer);
  start_pieces(board, line, pieces, first_group, options, r);
  return r;
}

}  // namespace seqc::boards
