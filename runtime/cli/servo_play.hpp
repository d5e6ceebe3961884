// The words of `seqc play FILE`: what boards::play_live (runtime/boards/live.hpp) did, said
// the way the board's LiveStyle asks. A servo board (Moves) is told moves: each one's lateness
// is measured once it has left the port and p50/p99/max are reported at the end; a schedule the
// link cannot keep is refused, naming the first late move and by how much, with `seqc upload
// --run` as the fix (with --allow-late it is played anyway after a warning); the command
// returns when the last move has ended. A car (Stream) is told frames: the report gives their
// lateness and whether the stop frame was sent after an early end. Ctrl-C stops sending at once;
// exit status Interrupted.
#pragma once

#include <string>

#include "compiler/compile.hpp"
#include "runtime/boards/board.hpp"
#include "runtime/cli/context.hpp"
#include "runtime/cli/exit_codes.hpp"
#include "runtime/cli/music_play.hpp"

namespace seqc::cli {

// What `seqc play` was given.
struct PlayArgs {
  std::string file;  // for messages and the `seqc upload FILE --run` hint
  std::string port;
  bool strict = false;
  bool realtime = false;
  bool allow_late = false;  // play a schedule the link cannot keep, with a warning
  std::string trace;        // --trace FILE ("" = none)
  bool force = false;       // start even when a servo's first move is too fast from where it is
  MusicArgs music;          // --music, --audio-offset
};

// Opens the port `args` names for the board `compiled` is for, plays it live and says how it
// went. With args.music the song is decoded and the sound server reached first, the song
// started just before the first frame, and the first frame timed to finish arriving (plus the
// board's start delay) on its downbeat as heard; the song then plays to its end (Ctrl-C stops
// it and the robot). Where the servos report their positions, they are read first and a first move
// faster than a servo's max_speed from there is refused (InvalidInput, nothing moves) unless
// args.force (boards/first_move.hpp).
ExitCode play_on_board(Context& ctx, const compiler::CompileOutput& compiled, const PlayArgs& args);

// The same over a line that is already open (tests drive it over their own transport).
ExitCode play_on_line(Context& ctx, const compiler::CompileOutput& compiled,
                      const boards::Line& line, const PlayArgs& args = {});

}  // namespace seqc::cli
