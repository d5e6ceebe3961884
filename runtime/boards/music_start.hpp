// A robot started on a song's downbeat as heard (`seqc upload --run --music`, `seqc play
// --music`, a show with `music:`). The song is started on the audio output first; its playback
// clock then dates the downbeat as heard (runtime/audio/playback_sync.hpp has the formula), and
// the robot's start command is written so that its last byte reaches the board the board's
// start delay before that instant. Songs whose downbeat comes too soon for that are played
// after a lead-in of silence, so the robot is never late by construction. Interrupts and the
// safe stop are the player's (runtime/player): one path stops the robot, and the caller stops
// the audio output in the same path.
#pragma once

#include <atomic>
#include <cstdint>
#include <optional>

#include "runtime/audio/audio_files.hpp"
#include "runtime/audio/audio_output.hpp"
#include "runtime/audio/playback_sync.hpp"
#include "runtime/boards/board.hpp"
#include "runtime/io/clock.hpp"
#include "runtime/player/player.hpp"

namespace seqc::boards {

// The least time from the start of what is played to the downbeat: the output's start-up
// (pa_simple settles in about 0.2 s) and the robot's wire time fit in it with room to spare.
inline constexpr io::Duration kMinDownbeat = std::chrono::milliseconds(500);

struct SongStart {
  audio::PlaybackClock clock;  // read once the song plays
  io::Duration downbeat{0};    // bar 1 beat 1 in what is played (the lead-in included)
  io::Duration lead_in{0};     // silence played before the song
};

// Plays `song` from its start, after a lead-in of silence when its downbeat is sooner than
// kMinDownbeat; an Error when the output refuses.
Result<SongStart> start_song(audio::AudioOutput& output, const audio::MonoAudio& song,
                             io::Duration downbeat);

// The timing of a start command against the song.
audio::StartTiming start_timing(const Board& board, const SongStart& song,
                                io::Duration audio_offset, std::size_t command_bytes,
                                double seconds_per_byte);

// How a start went: when it was planned, when its write began, and so when its last byte
// reached the board; skew = that arrival + the board's start delay - the downbeat as heard.
struct SyncedStart {
  audio::StartPlan plan;
  io::Duration wire{0};
  io::Duration board_delay{0};
  std::optional<io::TimePoint> written;  // unset when nothing was written
  io::TimePoint arrived{0};
  io::Duration skew{0};
};
SyncedStart synced_start(const audio::StartPlan& plan, io::Duration wire, io::Duration board_delay,
                         std::optional<io::TimePoint> written);

// An instant on the clock `from` as the same instant on `to`: as far ahead of `to`'s now as it
// lies ahead of `from`'s. For a robot on an in-process emulator's own clock, whose start is
// dated on the host's clock by the song; `t` itself when they are one clock.
io::TimePoint carried_over(io::TimePoint t, io::Clock& from, io::Clock& to);

// A stored board's group started on the downbeat: its run frame written at plan.write_at (on
// line.clock, the output's clock; or, given `song_clock` for an emulator on its own clock,
// carried over from it), then its start confirmed the board's way.
// After an early end (Ctrl-C, a failed write) the board's stop frame is written.
struct MusicRunReport {
  SyncedStart start;
  player::PlayReport play;
  std::optional<RunOutcome> run;  // when the play completed and the board confirms runs
};
MusicRunReport run_on_downbeat(const Board& board, const Line& line, std::uint8_t group,
                               std::uint16_t times, const SongStart& song,
                               io::Duration audio_offset, io::Clock* song_clock = nullptr);

// Waits, polling `interrupted`, until the output has played everything; false if interrupted.
bool wait_for_song(audio::AudioOutput& output, io::Clock& clock,
                   const std::atomic<bool>* interrupted);

}  // namespace seqc::boards
