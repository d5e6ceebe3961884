#include "runtime/boards/music_session.hpp"

#include <cmath>
#include <utility>

#include "runtime/audio/sndfile_audio.hpp"

namespace seqc::boards {

MusicOpen open_music(const compiler::Song& song, io::Duration audio_offset,
                     audio::AudioReader* reader, audio::AudioOutputFactory* outputs,
                     MusicSession& out) {
  out.file = song.file;
  out.downbeat = io::Duration{std::llround(song.downbeat.value() * 1e6)};
  out.audio_offset = audio_offset;
  if (outputs == nullptr) return {MusicOpenStatus::NoOutput, ""};
  audio::SndfileAudioReader disk;
  Result<audio::MonoAudio> decoded = (reader != nullptr ? *reader : disk).read(song.file);
  if (!decoded) return {MusicOpenStatus::Unreadable, decoded.error().message};
  out.song = std::move(decoded).value();
  Result<std::unique_ptr<audio::AudioOutput>> output = outputs->open();
  if (!output) return {MusicOpenStatus::OutputRefused, output.error().message};
  out.output = std::move(output).value();
  return {};
}

Status start_music(MusicSession& music) {
  Result<SongStart> started = start_song(*music.output, music.song, music.downbeat);
  if (!started) return started.error();
  music.started = *started;
  return Ok{};
}

bool play_song_out(MusicSession& music, io::Clock& clock, const std::atomic<bool>* interrupted) {
  const bool whole = wait_for_song(*music.output, clock, interrupted);
  music.output->stop();
  return whole;
}

LiveSongStart live_song_start(const Board& board, const MusicSession& music,
                              std::size_t first_frame_bytes, double seconds_per_byte,
                              io::Clock& host, io::Clock& line_clock) {
  const audio::StartTiming timing =
      start_timing(board, *music.started, music.audio_offset, first_frame_bytes, seconds_per_byte);
  LiveSongStart s;
  s.plan = audio::plan_start(music.started->clock, timing);
  s.wire = timing.wire;
  // The player writes each frame its own wire time early; the board's delay is the rest.
  s.start = LiveStart{s.plan.downbeat_heard, timing.board_delay};
  if (music.robot_in_emulated_time) s.start.at = carried_over(s.start.at, host, line_clock);
  return s;
}

std::optional<io::TimePoint> first_written(const player::PlayReport& play) {
  if (play.tracks.empty() || !play.tracks[0].first) return std::nullopt;
  return play.started + *play.tracks[0].first;
}

}  // namespace seqc::boards
