// seqc's entry point: wires the real clock, disk and terminal into the CLI and runs it.
#include <sys/ioctl.h>
#include <unistd.h>
#include <atomic>
#include <csignal>
#include <cstdlib>
#include <iostream>

#include "runtime/audio/pulse_output.hpp"
#include "runtime/audio/sndfile_audio.hpp"
#include "runtime/boards/song_reader.hpp"
#include "runtime/cli/app.hpp"
#include "runtime/io/clock.hpp"
#include "runtime/io/disk.hpp"

namespace {
// The one piece of process-wide state: a signal handler can only reach a static.
std::atomic<bool> g_interrupted{false};
void on_sigint(int) { g_interrupted.store(true); }
}  // namespace

int main(int argc, char** argv) {
  struct sigaction sa {};
  sa.sa_handler = on_sigint;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
  std::signal(SIGPIPE, SIG_IGN);

  seqc::io::SteadyClock clock;
  seqc::io::DiskFileReader files;
  seqc::cli::Context ctx{std::cout,      std::cerr, clock, files, ::isatty(STDERR_FILENO) == 1,
                         &g_interrupted, &std::cin};
  seqc::audio::SndfileAudioReader audio;
  seqc::boards::AudioSongReader songs(audio);
  ctx.songs = &songs;
  ctx.audio_files = &audio;
  seqc::audio::PulseAudioOutputFactory speakers(clock, "seqc");
  ctx.audio_output = &speakers;
  const char* no_color = std::getenv("NO_COLOR");  // https://no-color.org: set and non-empty
  ctx.no_color_env = no_color != nullptr && *no_color != '\0';
  struct winsize ws {};
  if (ctx.err_is_terminal && ::ioctl(STDERR_FILENO, TIOCGWINSZ, &ws) == 0) {
    ctx.terminal_columns = ws.ws_col;
  }
  return seqc::cli::run(argc, argv, ctx);
}
