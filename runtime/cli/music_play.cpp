#include "runtime/cli/music_play.hpp"

#include <cmath>
#include <optional>
#include <ostream>

#include <fmt/format.h>

#include "runtime/cli/clock_option.hpp"
#include "runtime/io/time_text.hpp"

namespace seqc::cli {
namespace {

// "1.50 ms after it", "2.00 ms before it", "on it" (to the hundredth of a millisecond).
std::string relative_text(io::Duration skew) {
  const double ms = std::chrono::duration<double, std::milli>(skew).count();
  if (std::fabs(ms) < 0.005) return "on it";
  return fmt::format("{:.2f} ms {} it", std::fabs(ms), ms > 0 ? "after" : "before");
}

}  // namespace

void add_music_options(CLI::App& cmd, MusicArgs& args, CLI::Option* needs, bool rig_option) {
  CLI::Option* music = cmd.add_flag(
      "--music", args.music,
      "Play the song of the file's `music:` block and start the robot on its downbeat as heard "
      "(docs/music.md)");
  if (needs != nullptr) music->needs(needs);
  args.audio_offset =
      cmd.add_option("--audio-offset", args.audio_offset_ms,
                     "With --music: milliseconds the sound reaches you after the audio API says "
                     "it does (speakers, Bluetooth; may be negative)")
          ->check(CLI::Range(-5000.0, 5000.0))
          ->needs(music);
  if (rig_option) {
    cmd.add_option("--rig", args.rig,
                   "Rig file (YAML; docs/music.md): its audio_offset, unless --audio-offset is "
                   "given");
  }
}

ExitCode open_music(Context& ctx, const compiler::Song& song, const MusicArgs& args,
                    MusicSession& out) {
  io::Duration offset{std::llround(args.audio_offset_ms * 1e6)};
  std::string offset_from;
  const bool offset_given = args.audio_offset != nullptr && args.audio_offset->count() > 0;
  if (!offset_given && !args.rig.empty()) {
    std::optional<compiler::Rig> rig;
    if (const ExitCode e = read_rig(ctx, args.rig, rig); e != ExitCode::Ok) return e;
    if (rig->audio_offset) {
      offset = *rig->audio_offset;
      offset_from = args.rig;
    }
  }
  out.audio_offset_from = offset_from;
  const boards::MusicOpen opened =
      boards::open_music(song, offset, ctx.audio_files, ctx.audio_output, out);
  switch (opened.status) {
    case boards::MusicOpenStatus::Ok:
      return ExitCode::Ok;
    case boards::MusicOpenStatus::NoOutput:
      ctx.err << "seqc: error: --music: no audio output was given to seqc\n";
      return ExitCode::Internal;
    case boards::MusicOpenStatus::Unreadable:
      ctx.err << "seqc: error: " << opened.message << "\n";
      return ExitCode::FileError;
    case boards::MusicOpenStatus::OutputRefused:
      break;
  }
  ctx.err << "seqc: error: --music: " << opened.message
          << "; nothing was sent\n  hint: start PulseAudio (or PipeWire's pulse server), or set "
             "PULSE_SERVER\n";
  return ExitCode::PortUnavailable;
}

ExitCode open_music(Context& ctx, const compiler::CompileOutput& compiled, const std::string& path,
                    const MusicArgs& args, MusicSession& out) {
  const compiler::Song* song = boards::song_of(compiled);
  if (song == nullptr) {
    ctx.err << "seqc: error: --music: " << path
            << " has no `music:` block, so there is no song to play (docs/music.md)\n";
    return ExitCode::Usage;
  }
  return open_music(ctx, *song, args, out);
}

bool start_music(Context& ctx, MusicSession& music) {
  if (Status started = boards::start_music(music); !started) {
    ctx.err << "seqc: error: --music: " << started.error().message << "\n";
    return false;
  }
  return true;
}

std::string heard_text(const MusicSession& music, const audio::StartPlan& p) {
  std::string text = "music: downbeat heard at +" +
                     io::seconds_text(p.downbeat_heard - p.audio_started) + " (output latency " +
                     io::ms_text(p.latency, 1);
  if (music.audio_offset != io::Duration{0}) {
    const double ms = std::chrono::duration<double, std::milli>(music.audio_offset).count();
    text += music.audio_offset_from.empty()
                ? fmt::format(", --audio-offset {:g} ms", ms)
                : fmt::format(", audio_offset {:g} ms from {}", ms, music.audio_offset_from);
  }
  if (music.started && music.started->lead_in > io::Duration{0}) {
    text += ", after " + io::seconds_text(music.started->lead_in) + " of silence";
  }
  return text + ")";
}

std::string sync_text(const MusicSession& music, const boards::SyncedStart& start,
                      const std::string& command) {
  std::string text = heard_text(music, start.plan) + "; ";
  if (!start.written) return text + command + " was not sent";
  if (music.robot_in_emulated_time) {
    return text + command +
           " went to the in-process emulator, which keeps no real time: no start skew is measured";
  }
  text += "robot started " + relative_text(start.skew) + " (" + command + " written " +
          io::ms_text(*start.written - start.plan.write_at, 2) + " after its time, " +
          io::ms_text(start.wire, 2) + " on the wire";
  if (start.board_delay != io::Duration{0}) {
    text += ", board start delay " + io::ms_text(start.board_delay, 1);
  }
  return text + ")";
}

}  // namespace seqc::cli
