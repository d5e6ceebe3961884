#include "runtime/boards/show.hpp"

#include <algorithm>
#include <chrono>
#include <utility>

#include "runtime/audio/playback_sync.hpp"

namespace seqc::boards {
namespace {

// A short lead, beyond the earliest write, so the first deadline is in the future for every
// performer.
constexpr io::Duration kLead = std::chrono::milliseconds(20);

bool stores(const Board& board) { return board.run_frame != nullptr; }

}  // namespace

ShowReport perform(std::vector<Performer>& performers, io::Clock& clock,
                   const std::atomic<bool>* interrupted, io::Duration reply_timeout,
                   std::optional<io::TimePoint> start_at) {
  ShowReport report;
  report.performers.resize(performers.size());
  std::vector<player::Track> tracks;
  for (Performer& p : performers) {
    player::Track track;
    track.transport = p.port->transport.get();
    if (stores(*p.board)) {
      // The stored group starts at the common start, with the board's own run command.
      track.frames.push_back({io::Duration{0}, p.board->run_frame(p.group, 1)});
      if (p.board->stop_frame != nullptr) track.safe_stop = p.board->stop_frame();
    } else {
      if (p.board->live_frames == nullptr) {
        report.error = p.name + ": " + std::string(p.board->name) + " plays nothing live";
        return report;
      }
      auto frames = p.board->live_frames(*p.output);
      if (!frames) {
        report.error = p.name + ": " + frames.error().message;
        return report;
      }
      track.frames = std::move(frames).value();
      if (p.board->safe_stop != nullptr) track.safe_stop = p.board->safe_stop();
    }
    PerformerReport& mine = report.performers[tracks.size()];
    if (!track.frames.empty()) {
      mine.wire =
          audio::wire_time(track.frames.front().bytes.size(), track.transport->seconds_per_byte());
    }
    mine.delay = p.board->start_delay;
    track.early = mine.wire + mine.delay;
    tracks.push_back(std::move(track));
  }

  player::PlayOptions options;
  options.interrupted = interrupted;
  io::Duration earliest{0};
  for (const player::Track& t : tracks) earliest = std::max(earliest, t.early);
  options.lead = kLead + earliest;
  options.start_at = start_at;
  report.play = player::play(tracks, clock, options);

  for (std::size_t i = 0; i < performers.size(); ++i) {
    if (i < report.play.tracks.size()) report.performers[i].track = report.play.tracks[i];
  }
  if (report.play.end != player::PlayEnd::Completed) return report;
  // The replies to the run commands were kept by the transports while the streams played.
  for (std::size_t i = 0; i < performers.size(); ++i) {
    Performer& p = performers[i];
    if (!stores(*p.board) || p.board->confirm_run == nullptr) continue;
    const Line line{*p.port->transport, *p.port->clock, interrupted, reply_timeout};
    report.performers[i].run = p.board->confirm_run(line, p.group, 1);
  }
  return report;
}

}  // namespace seqc::boards
