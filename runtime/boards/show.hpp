// A show: several boards started on one deadline. Each performer is one track of one player:
// a board that stores its group gets its run frame at the common start, a streamed board gets
// its live frames from the same start. "At the start" means when the start command finishes
// arriving at the board plus the board's start delay, not when it is written: each track is
// written early by its first frame's wire time (bytes x 10 bits / baud: a 7-byte GroupRun at
// 9600 baud takes 7.29 ms, a 13-byte car packet at 115200 1.13 ms) and its board's
// start_delay. After an early end every track's safe stop is written.
// When the play completes, every stored performer's start is confirmed the board's own way;
// the replies are read after the streams end, from what the transport kept.
#pragma once

#include <atomic>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "compiler/compile.hpp"
#include "compiler/show.hpp"
#include "runtime/boards/board.hpp"
#include "runtime/boards/first_move.hpp"
#include "runtime/boards/ports.hpp"
#include "runtime/boards/trace_file.hpp"
#include "runtime/io/clock.hpp"
#include "runtime/player/player.hpp"
#include "runtime/upload/uploader.hpp"

namespace seqc::boards {

struct Performer {
  std::string name;
  const Board* board = nullptr;
  OpenedPort* port = nullptr;
  const compiler::CompileOutput* output = nullptr;
  std::uint8_t group = 0;
};

struct PerformerReport {
  player::TrackReport track;
  io::Duration wire{0};   // its first frame's time on the wire
  io::Duration delay{0};  // its board's start delay
  // When its first frame finished arriving plus the start delay, from the common start: when
  // it started moving.
  std::optional<io::Duration> started() const {
    if (!track.first) return std::nullopt;
    return *track.first + wire + delay;
  }
  std::optional<RunOutcome> run;  // stored performers
};

struct ShowReport {
  player::PlayReport play;
  std::vector<PerformerReport> performers;
  // Not empty when a streamed performer's frames could not be made: nothing was sent.
  std::string error;
  // The latest performer's start less the earliest's (PerformerReport::started, unset as 0).
  io::Duration start_skew() const;
};

// `start_at`: the common start at this instant (a song's downbeat as heard) instead of shortly
// after the call.
ShowReport perform(std::vector<Performer>& performers, io::Clock& clock,
                   const std::atomic<bool>* interrupted, io::Duration reply_timeout,
                   std::optional<io::TimePoint> start_at = std::nullopt);

// One performer of a show as `seqc show` opens it: the performer, its board, its trace file
// (PREFIX-NAME.trace with --trace PREFIX) and its port. The trace is declared before the port,
// so it outlives it.
struct ShowStage {
  const compiler::Performer* performer = nullptr;
  const Board* board = nullptr;
  TraceFile trace;
  std::optional<OpenedPort> port;
};

// Why a stage did not open: the show file gives the performer no port, its trace file
// (`trace_path`) cannot be written, or its port does not open (`request`, `failure`).
enum class StageProblem { None, NoPort, TraceUnwritable, PortFailed };
struct StageOpen {
  StageProblem problem = StageProblem::None;
  std::string trace_path;
  PortRequest request;
  PortFailure failure;
};

// Opens `p`'s stage in that order: its trace file when `trace_prefix` is not empty, then the
// port for the board its output is for, traced in place. Stops at the first problem.
StageOpen open_stage(const compiler::Performer& p, const std::string& trace_prefix,
                     io::Clock& clock, const Hooks& hooks, ShowStage& stage);

// The stage's group planned for its board (plan_for, into the performer's group).
Result<Plan> stage_plan(const ShowStage& stage);
// Stores `plan` over the stage's port (upload, into the performer's group).
upload::UploadResult upload_stage(const ShowStage& stage, const Plan& plan,
                                  const std::atomic<bool>* interrupted,
                                  upload::UploadObserver* observer);

// The first stage (in order) whose first move is too fast from where its servos are: every
// stage with a servo program is read on its board's way (first_move_too_fast); nullopt when
// every one is safe.
struct UnsafeStage {
  std::size_t stage = 0;
  FirstMoveTooFast too_fast;
};
std::optional<UnsafeStage> first_unsafe_stage(std::vector<ShowStage>& stages,
                                              const std::atomic<bool>* interrupted);

// The opened stages as perform() takes them.
std::vector<Performer> performers_of(std::vector<ShowStage>& stages);

// Writes every stage's stop frame, where its board has one: the stop after an interrupted song.
void stop_stages(std::vector<ShowStage>& stages);

}  // namespace seqc::boards
