// seqc play FILE [--port P] [--strict] [--allow-late] [--realtime] [--music [--audio-offset MS]]:
// streams a compiled sequence to a board live, each frame sent at its time on the host's clock,
// nothing stored: the Raspblock car board, or a servo controller without storing a group
// (servo_play.hpp has the words, runtime/boards/live.hpp the order of the steps). With --music
// the song of the file's `music:` block plays with it, the first frame on its downbeat.
#include <memory>
#include <ostream>
#include <string>

#include <CLI/CLI.hpp>

#include "runtime/boards/board.hpp"
#include "runtime/cli/commands.hpp"
#include "runtime/cli/compile_report.hpp"
#include "runtime/cli/realtime_option.hpp"
#include "runtime/cli/run_compile.hpp"
#include "runtime/cli/servo_play.hpp"
#include "runtime/cli/trace_option.hpp"

namespace seqc::cli {

bool explain_no_storage(const compiler::CompileOutput& output, const std::string& path,
                        std::ostream& err) {
  if (!output.program) return false;
  const boards::Board& board = boards::board_for(output);
  if (board.plan != nullptr) return false;
  err << "seqc: error: " << path << " is for the " << board.name
      << " board, which has no storage: it cannot keep a sequence to run "
         "later, only follow one streamed to it live\n"
         "  hint: play it with `seqc play "
      << path << " --port PORT` (e.g. --port /dev/ttyAMA0)\n";
  return true;
}

void add_play_command(CLI::App& app, Context& ctx, Outcome& result) {
  auto opts = std::make_shared<PlayArgs>();
  CLI::App* cmd = app.add_subcommand(
      "play",
      "Stream a sequence to a device live, each frame at its time (the Raspblock car board,\n"
      "or the servo controller without storing a group); Ctrl-C stops (exit 130)");
  cmd->add_option("FILE", opts->file, "Choreography file (.yaml)")->required();
  cmd->add_option("--port", opts->port,
                  "Raspblock: serial port at 115200 baud (/dev/ttyAMA0, ttyUSB0, a pty from "
                  "`seqc emulate raspblock`) or emu:raspblock. Servo controller: as for `seqc "
                  "upload` (default: the one connected; emu:xarm)");
  cmd->add_flag("--strict", opts->strict, "Treat warnings as errors");
  cmd->add_flag("--allow-late", opts->allow_late,
                "Servo controller: play a schedule the link cannot keep (moves leave late)");
  add_trace_option(*cmd, opts->trace);
  add_music_options(*cmd, opts->music);
  cmd->add_flag("--force", opts->force,
                "Servo controller: start even when a servo's first move, from where it reports "
                "it is, is faster than its max_speed");
  add_realtime_option(
      *cmd, opts->realtime,
      "Send with real-time (SCHED_FIFO) priority, so a busy machine cannot delay frames");
  cmd->callback([&ctx, &result, opts] {
    Compiled c = compile_for_run(ctx, opts->file, opts->strict, opts->port);
    result.code = c.code;
    if (!c.output.program) return;
    // The whole play: opening the port and the song are short beside it.
    const auto realtime = realtime_stretch(ctx, opts->realtime);
    result.code = play_on_board(ctx, c.output, *opts);
  });
}

}  // namespace seqc::cli
