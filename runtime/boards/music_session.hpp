// The song beside the robot, held while a command runs (`seqc play --music`, `seqc upload --run
// --music`, a show with `music:`): the song of a `music:` block decoded (runtime/audio) and the
// sound server reached before anything is sent to a board, then the song started just before
// the robot (music_start.hpp times the robot's start to its downbeat as heard) and played to its
// end. Returns data and status only; the CLI words them.
#pragma once

#include <atomic>
#include <memory>
#include <optional>
#include <string>

#include "compiler/compile.hpp"
#include "compiler/show.hpp"
#include "runtime/audio/audio_files.hpp"
#include "runtime/audio/audio_output.hpp"
#include "runtime/boards/live.hpp"
#include "runtime/boards/music_start.hpp"
#include "runtime/io/clock.hpp"
#include "runtime/player/player.hpp"

namespace seqc::boards {

// A song decoded and its output open, not yet playing; the output is stopped when this goes.
class MusicSession {
 public:
  MusicSession() = default;
  MusicSession(MusicSession&&) = default;
  MusicSession& operator=(MusicSession&&) = default;
  ~MusicSession() {
    if (output) output->stop();
  }
  std::string file;
  audio::MonoAudio song;
  io::Duration downbeat{0};
  io::Duration audio_offset{0};
  // Where audio_offset came from when a rig file gave it (its path), for the report; "" when it
  // is --audio-offset's (or none).
  std::string audio_offset_from;
  std::unique_ptr<audio::AudioOutput> output;
  std::optional<SongStart> started;
  // The robot is an in-process emulator on its own clock (boards::OpenedPort::own_clock): the
  // song is dated on the host's clock and the start on the emulator's, so no skew is measured.
  bool robot_in_emulated_time = false;
};

// A file's song and a show's one song are the compiler's (compiler/show.hpp).
using compiler::show_song;
using compiler::ShowSong;
using compiler::song_of;

// Why a song could not be made ready: no audio output was given, the file could not be
// decoded, or the output refused to open. `message` is the lower layer's.
enum class MusicOpenStatus { Ok, NoOutput, Unreadable, OutputRefused };
struct MusicOpen {
  MusicOpenStatus status = MusicOpenStatus::Ok;
  std::string message;
};

// Fills `out` for `song`: its file, downbeat and `audio_offset`, the song decoded by `reader`
// (null: libsndfile on the disk) and an output opened by `outputs` (null: refused, NoOutput,
// before anything is read).
MusicOpen open_music(const compiler::Song& song, io::Duration audio_offset,
                     audio::AudioReader* reader, audio::AudioOutputFactory* outputs,
                     MusicSession& out);

// Starts the session's song (start_song) and keeps its start in `music.started`; the output's
// refusal otherwise.
Status start_music(MusicSession& music);

// Waits on `clock` (the robot's line's) until the song has played, polling `interrupted`, then
// stops the output; false if interrupted.
bool play_song_out(MusicSession& music, io::Clock& clock, const std::atomic<bool>* interrupted);

// A live play's first frame on the started song's downbeat as heard (the start of
// play_live's hooks): the frame of `first_frame_bytes` is written so that it finishes arriving,
// plus the board's start delay, then. `plan` and `wire` are what synced_start reports against.
// With no bytes, `plan` is the downbeat alone (a show's tracks keep their own wire times).
// Requires music.started.
struct LiveSongStart {
  audio::StartPlan plan;
  io::Duration wire{0};
  LiveStart start;
};
// `host`: the clock the song is dated on; when music.robot_in_emulated_time, the start is carried
// over to `line_clock` (carried_over).
LiveSongStart live_song_start(const Board& board, const MusicSession& music,
                              std::size_t first_frame_bytes, double seconds_per_byte,
                              io::Clock& host, io::Clock& line_clock);

// When the first frame of `play` began to be written, on its clock; nullopt when none was.
std::optional<io::TimePoint> first_written(const player::PlayReport& play);

}  // namespace seqc::boards
