// Live play: a compiled program's frames sent on their deadlines to one board as they happen,
// nothing stored. The order is fixed for every board (frames, size check, schedule check,
// probe, play, wait for the last move to end); the Board row says which of those steps apply.
// It returns a status and the data to report; the CLI words it (board.style) and picks the exit
// code. The hooks let the CLI print its lines at the moments they belong to.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "compiler/compile.hpp"
#include "runtime/boards/board.hpp"
#include "runtime/io/clock.hpp"
#include "runtime/player/player.hpp"

namespace seqc::boards {

enum class LiveStatus {
  Played,
  Interrupted,
  InterruptedAtEnd,
  WriteFailed,
  FrameTooBig,
  LateSchedule,
  NoBoard,
  BadProgram,
  NotStarted  // LiveHooks::start refused (it said why): nothing was sent
};

// The program step a live frame comes from, for the messages that name a move: its start and
// where the source writes it.
struct FrameOrigin {
  std::uint64_t start_ms = 0;
  seqc::Location source;
};

struct LiveReport {
  LiveStatus status = LiveStatus::Played;
  std::vector<player::ScheduledFrame> frames;
  std::uint64_t length_ms = 0;  // how long the program runs: when its last move ends
  // One per frame when the program is made of steps (a servo program is played one frame per
  // keyframe); empty for a stream.
  std::vector<FrameOrigin> origins;
  std::optional<std::size_t> too_big;  // its limit: line.transport.max_frame_bytes()
  player::ScheduleCheck check;         // boards with check_schedule
  Outcome probe;                       // NoBoard: why
  player::PlayReport play;
  std::string error;  // BadProgram
};

// When the first frame is due instead of when the play begins (a song's downbeat as heard), and
// how much earlier than their own wire time the frames are written (the board's start delay),
// so each finishes arriving at its time.
struct LiveStart {
  io::TimePoint at{0};
  io::Duration early{0};
};

struct LiveHooks {
  std::function<void(const LiveReport&)> checked;   // after the schedule check, before the probe
  std::function<void(const LiveReport&)> starting;  // after the probe, before the first frame
  std::function<void(std::size_t index, io::Duration at)> sent;
  // Asked just before the first frame, with the frames made; unset: start at once; nullopt:
  // do not start (NotStarted).
  std::function<std::optional<LiveStart>(const LiveReport&)> start;
};

LiveReport play_live(const Board& board, const compiler::CompileOutput& output, const Line& line,
                     bool allow_late, const LiveHooks& hooks = {});

}  // namespace seqc::boards
