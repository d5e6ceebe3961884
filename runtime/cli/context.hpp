// Everything a subcommand may touch outside itself, passed in, so tests run subcommands
// in-process with string streams, a manual clock and emulated boards. The emulators reach the
// boards library as its own boards::Hooks, so the CLI names none of them.
#pragma once

#include <atomic>
#include <iosfwd>

#include "base/source.hpp"
#include "runtime/audio/audio_files.hpp"
#include "runtime/audio/audio_output.hpp"
#include "runtime/boards/hooks.hpp"
#include "runtime/io/clock.hpp"
#include "runtime/io/realtime.hpp"

namespace seqc::cli {

struct Context {
  std::ostream& out;  // data
  std::ostream& err;  // diagnostics, progress, "seqc: error: ..."
  io::Clock& clock;
  seqc::FileReader& files;
  bool err_is_terminal = false;  // progress bar vs plain lines
  // Set on SIGINT, SIGTERM or SIGHUP once a command has said it stops cleanly (below); it polls
  // the flag and stops the robot, the song or the server before it returns Interrupted.
  const std::atomic<bool>* interrupted = nullptr;
  // Standard input, for commands that accept "-" as a file name (e.g. `seqc decode -`).
  std::istream* in = nullptr;
  // Until a command sets this (stop_cleanly_from_now), a stop signal ends seqc at once with
  // 128 + its number: a command with nothing to stop (check, compile, plot...) never makes the
  // user wait for a slow input. Null when run in-process (tests), where no handler is set.
  std::atomic<bool>* stops_cleanly = nullptr;
  // What `--port emu:NAME` reaches instead of a fresh emulator (runtime/boards/hooks.hpp): tests
  // prepare it (stored groups, faults) and read what it received afterwards, and several
  // commands can share it.
  boards::Hooks hooks{};
  // From the environment, read once in main: NO_COLOR set and non-empty, and the terminal's
  // width in columns (0 when stderr is not a terminal).
  bool no_color_env = false;
  int terminal_columns = 0;

  // Set from the global options before any subcommand runs:
  // -q/--quiet = -1 (errors and data only), 0, -v/--verbose = 1 (every re-send, port, probe).
  int verbosity = 0;
  bool color = false;  // diagnostics in colour (--color, NO_COLOR, err_is_terminal)
  // Decodes a choreography's `music:` song for the commands that check it; null: not checked.
  seqc::SongReader* songs = nullptr;
  // --music: where a song is decoded (null: libsndfile on the disk) and played (null: no audio).
  audio::AudioReader* audio_files = nullptr;
  audio::AudioOutputFactory* audio_output = nullptr;
  // --realtime: what raises the thread that keeps time (null: the system's SCHED_FIFO).
  io::Scheduler* scheduler = nullptr;
};

// Called by a command before it opens a port, a trace, a song or a server: from then on a stop
// signal sets `interrupted` and the command ends what it started before it returns.
inline void stop_cleanly_from_now(Context& ctx) {
  if (ctx.stops_cleanly != nullptr) ctx.stops_cleanly->store(true);
}

}  // namespace seqc::cli
