// The song beside the robot, in words: `--music` and `--audio-offset MS` on `seqc play` and
// `seqc upload --run`, and a show whose performer has `music:`; without --audio-offset, the
// `--rig` file's audio_offset. The session itself (the song
// decoded, the sound server reached before anything is sent to a board, the song started just
// before the robot) is boards::MusicSession (runtime/boards/music_session.hpp); this file words
// its failures and its report. The report is one line on stderr: when the downbeat is heard,
// from the audio's start, and how far from it the robot started as seqc measured it; an
// in-process emulator (emu:xarm, emu:lsc6) keeps no real time, so for one the line says that no
// skew is measured.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

#include "compiler/compile.hpp"
#include "runtime/boards/music_session.hpp"
#include "runtime/cli/context.hpp"
#include "runtime/cli/exit_codes.hpp"

namespace seqc::cli {

struct MusicArgs {
  bool music = false;
  double audio_offset_ms = 0;                 // --audio-offset: what no audio API sees
  const CLI::Option* audio_offset = nullptr;  // --audio-offset itself, to tell whether it was given
  // The rig file (--rig): its audio_offset is used when --audio-offset is not given, as its
  // clock_ppm is when --clock-ppm is not.
  std::string rig;
};

// --music and --audio-offset, and --rig unless the command has it already (`rig_option` false:
// the command copies its --rig into MusicArgs::rig). `needs`: an option --music needs (upload's
// --run), or null.
void add_music_options(CLI::App& cmd, MusicArgs& args, CLI::Option* needs = nullptr,
                       bool rig_option = true);

using boards::MusicSession;  // runtime/boards/music_session.hpp

// The song of `song` (a file's or a show's `music:`): decoded, and the sound server reached.
// An error is said on ctx.err and its exit status returned.
ExitCode open_music(Context& ctx, const compiler::Song& song, const MusicArgs& args,
                    MusicSession& out);
// The compiled file's song, or an error when it has no `music:` block.
ExitCode open_music(Context& ctx, const compiler::CompileOutput& compiled, const std::string& path,
                    const MusicArgs& args, MusicSession& out);

// Starts the song; false (said on ctx.err) when the output refuses.
bool start_music(Context& ctx, MusicSession& music);

// "music: downbeat heard at +0.820 s (output latency 50.0 ms, --audio-offset 20 ms, after 0.300 s
// of silence)", the lead-in said when one was played: every song-playing command's report opens
// so. sync_text adds "; robot started 0.02 ms after it (GroupRun written 0.01 ms after its time,
// 7.29 ms on the wire)", or, for a robot in emulated time, that `command` went to the in-process
// emulator and no skew is measured.
std::string heard_text(const MusicSession& music, const audio::StartPlan& plan);
std::string sync_text(const MusicSession& music, const boards::SyncedStart& start,
                      const std::string& command);

}  // namespace seqc::cli
