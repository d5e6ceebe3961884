#include "runtime/cli/music_play.hpp"

#include <cmath>
#include <ostream>

#include <fmt/format.h>

#include "runtime/audio/sndfile_audio.hpp"
#include "runtime/io/time_text.hpp"

namespace seqc::cli {
namespace {

const compiler::Song* song_of(const compiler::CompileOutput& compiled) {
  if (const compiler::ServoProgram* p = compiled.servo_program(); p && p->timeline.song) {
    return &*p->timeline.song;
  }
  if (const compiler::RaspblockProgram* p = compiled.raspblock_program(); p && p->timeline.song) {
    return &*p->timeline.song;
  }
  return nullptr;
}

// "1.50 ms after it", "2.00 ms before it", "on it" (to the hundredth of a millisecond).
std::string relative_text(io::Duration skew) {
  const double ms = std::chrono::duration<double, std::milli>(skew).count();
  if (std::fabs(ms) < 0.005) return "on it";
  return fmt::format("{:.2f} ms {} it", std::fabs(ms), ms > 0 ? "after" : "before");
}

}  // namespace

void add_music_options(CLI::App& cmd, MusicArgs& args, CLI::Option* needs) {
  CLI::Option* music = cmd.add_flag(
      "--music", args.music,
      "Play the song of the file's `music:` block and start the robot on its downbeat as heard "
      "(docs/music.md)");
  if (needs != nullptr) music->needs(needs);
  cmd.add_option("--audio-offset", args.audio_offset_ms,
                 "With --music: milliseconds the sound reaches you after the audio API says it "
                 "does (speakers, Bluetooth; may be negative)")
      ->check(CLI::Range(-5000.0, 5000.0))
      ->needs(music);
}

ExitCode open_music(Context& ctx, const compiler::Song& song, const MusicArgs& args,
                    MusicSession& out) {
  out.file = song.file;
  out.downbeat = io::Duration{std::llround(song.downbeat.value() * 1e6)};
  out.audio_offset = io::Duration{std::llround(args.audio_offset_ms * 1e6)};
  if (ctx.audio_output == nullptr) {
    ctx.err << "seqc: error: --music: no audio output was given to seqc\n";
    return ExitCode::Internal;
  }
  audio::SndfileAudioReader disk;
  audio::AudioReader& reader = ctx.audio_files != nullptr ? *ctx.audio_files : disk;
  Result<audio::MonoAudio> decoded = reader.read(song.file);
  if (!decoded) {
    ctx.err << "seqc: error: " << decoded.error().message << "\n";
    return ExitCode::FileError;
  }
  out.song = std::move(decoded).value();
  Result<std::unique_ptr<audio::AudioOutput>> output = ctx.audio_output->open();
  if (!output) {
    ctx.err << "seqc: error: --music: " << output.error().message
            << "; nothing was sent\n  hint: start PulseAudio (or PipeWire's pulse server), or set "
               "PULSE_SERVER\n";
    return ExitCode::PortUnavailable;
  }
  out.output = std::move(output).value();
  return ExitCode::Ok;
}

ExitCode open_music(Context& ctx, const compiler::CompileOutput& compiled, const std::string& path,
                    const MusicArgs& args, MusicSession& out) {
  const compiler::Song* song = song_of(compiled);
  if (song == nullptr) {
    ctx.err << "seqc: error: --music: " << path
            << " has no `music:` block, so there is no song to play (docs/music.md)\n";
    return ExitCode::Usage;
  }
  return open_music(ctx, *song, args, out);
}

bool start_music(Context& ctx, MusicSession& music) {
  Result<boards::SongStart> started = boards::start_song(*music.output, music.song, music.downbeat);
  if (!started) {
    ctx.err << "seqc: error: --music: " << started.error().message << "\n";
    return false;
  }
  music.started = *started;
  return true;
}

std::string sync_text(const MusicSession& music, const boards::SyncedStart& start,
                      const std::string& command) {
  const audio::StartPlan& p = start.plan;
  const io::Duration heard = p.downbeat_heard - p.audio_started;
  std::string text = "music: downbeat heard at +" + io::seconds_text(heard) + " (output latency " +
                     io::ms_text(p.latency, 1);
  if (music.audio_offset != io::Duration{0}) {
    text += fmt::format(", --audio-offset {:g} ms",
                        std::chrono::duration<double, std::milli>(music.audio_offset).count());
  }
  if (music.started && music.started->lead_in > io::Duration{0}) {
    text += ", after " + io::seconds_text(music.started->lead_in) + " of silence";
  }
  text += "); ";
  if (!start.written) return text + command + " was not sent";
  if (music.robot_in_emulated_time) {
    return text + command +
           " went to the in-process emulator, which keeps no real time: no start skew is measured";
  }
  text += "robot started " + relative_text(start.skew) + " (" + command + " written " +
          io::ms_text(*start.written - p.write_at, 2) + " after its time, " +
          io::ms_text(start.wire, 2) + " on the wire";
  if (start.board_delay != io::Duration{0}) {
    text += ", board start delay " + io::ms_text(start.board_delay, 1);
  }
  return text + ")";
}

bool play_song_out(Context& ctx, MusicSession& music, io::Clock& clock) {
  const bool whole = boards::wait_for_song(*music.output, clock, ctx.interrupted);
  music.output->stop();
  return whole;
}

}  // namespace seqc::cli
