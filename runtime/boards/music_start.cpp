#include "runtime/boards/music_start.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace seqc::boards {
namespace {

constexpr io::Duration kPollInterval = std::chrono::milliseconds(20);

}  // namespace

Result<SongStart> start_song(audio::AudioOutput& output, const audio::MonoAudio& song,
                             io::Duration downbeat) {
  SongStart s;
  s.lead_in = downbeat < kMinDownbeat ? kMinDownbeat - downbeat : io::Duration{0};
  const auto silent = static_cast<std::size_t>(
      std::llround(std::chrono::duration<double>(s.lead_in).count() * song.sample_rate));
  audio::PcmAudio pcm;
  pcm.channels = 1;
  pcm.sample_rate = song.sample_rate;
  pcm.samples.assign(silent, 0.0f);
  pcm.samples.insert(pcm.samples.end(), song.samples.begin(), song.samples.end());
  // The lead-in is a whole number of samples: the downbeat moves by exactly what is played.
  s.downbeat =
      downbeat + io::Duration{std::llround(static_cast<double>(silent) * 1e9 / song.sample_rate)};
  if (Status started = output.start(pcm); !started) return started.error();
  Result<audio::PlaybackClock> clock = output.clock();
  if (!clock) return clock.error();
  s.clock = *clock;
  return s;
}

audio::StartTiming start_timing(const Board& board, const SongStart& song,
                                io::Duration audio_offset, std::size_t command_bytes,
                                double seconds_per_byte) {
  audio::StartTiming t;
  t.downbeat = song.downbeat;
  t.audio_offset = audio_offset;
  t.wire = audio::wire_time(command_bytes, seconds_per_byte);
  t.board_delay = board.start_delay;
  return t;
}

SyncedStart synced_start(const audio::StartPlan& plan, io::Duration wire, io::Duration board_delay,
                         std::optional<io::TimePoint> written) {
  SyncedStart s;
  s.plan = plan;
  s.wire = wire;
  s.board_delay = board_delay;
  s.written = written;
  if (written) {
    s.arrived = *written + wire;
    s.skew = s.arrived + board_delay - plan.downbeat_heard;
  }
  return s;
}

io::TimePoint carried_over(io::TimePoint t, io::Clock& from, io::Clock& to) {
  if (&from == &to) return t;
  return to.now() + (t - from.now());
}

MusicRunReport run_on_downbeat(const Board& board, const Line& line, std::uint8_t group,
                               std::uint16_t times, const SongStart& song,
                               io::Duration audio_offset, io::Clock* song_clock) {
  MusicRunReport report;
  const Bytes command = board.run_frame(group, times);
  const audio::StartTiming timing =
      start_timing(board, song, audio_offset, command.size(), line.transport.seconds_per_byte());
  const audio::StartPlan plan = audio::plan_start(song.clock, timing);
  // A reply left from the upload must not be taken for the run's confirmation.
  line.transport.discard_input();
  player::Track track;
  track.transport = &line.transport;
  track.frames.push_back({io::Duration{0}, command});
  track.seconds_per_byte = line.transport.seconds_per_byte();
  track.early = timing.board_delay;
  if (board.stop_frame != nullptr) track.safe_stop = board.stop_frame();
  player::PlayOptions options;
  options.interrupted = line.interrupted;
  options.start_at = song_clock != nullptr
                         ? carried_over(plan.downbeat_heard, *song_clock, line.clock)
                         : plan.downbeat_heard;
  report.play = player::play(std::vector<player::Track>{track}, line.clock, options);
  std::optional<io::TimePoint> written;
  if (!report.play.tracks.empty() && report.play.tracks[0].first) {
    written = report.play.started + *report.play.tracks[0].first;
  }
  report.start = synced_start(plan, timing.wire, timing.board_delay, written);
  if (report.play.end == player::PlayEnd::Completed && board.confirm_run != nullptr) {
    report.run = board.confirm_run(line, group, times);
  }
  return report;
}

bool wait_for_song(audio::AudioOutput& output, io::Clock& clock,
                   const std::atomic<bool>* interrupted) {
  while (!output.finished()) {
    if (interrupted != nullptr && interrupted->load()) return false;
    clock.sleep_until(clock.now() + kPollInterval);
  }
  return true;
}

}  // namespace seqc::boards
