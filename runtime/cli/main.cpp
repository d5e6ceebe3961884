// seqc's entry point: wires the real clock, disk and terminal into the CLI and runs it.
#include <sys/ioctl.h>
#include <unistd.h>
#include <atomic>
#include <csignal>
#include <cstdlib>
#include <iostream>
#include <new>

#include "runtime/audio/pulse_output.hpp"
#include "runtime/audio/sndfile_audio.hpp"
#include "runtime/boards/song_reader.hpp"
#include "runtime/cli/app.hpp"
#include "runtime/cli/exit_codes.hpp"
#include "runtime/io/clock.hpp"
#include "runtime/io/disk.hpp"

namespace {
// The only process-wide state, as a signal handler can only reach a static: whether the command
// has said it stops cleanly (Context::stops_cleanly), the flag it then polls, and the first stop
// signal that arrived, which picks the exit status.
std::atomic<bool> g_stops_cleanly{false};
std::atomic<bool> g_interrupted{false};
std::atomic<int> g_signal{0};
void on_stop_signal(int signal) {
  // Nothing started that must be stopped: end now, as a shell reports a death by the signal.
  // _exit is async-signal-safe; an output file is only ever a temporary until its rename, and
  // io::write_file_safely holds these signals off while it writes one.
  if (!g_stops_cleanly.load()) ::_exit(128 + signal);
  int none = 0;
  g_signal.compare_exchange_strong(none, signal);
  g_interrupted.store(true);
}

int run_seqc(int argc, char** argv) {
  seqc::io::SteadyClock clock;
  seqc::io::DiskFileReader files;
  seqc::cli::Context ctx{std::cout,      std::cerr, clock, files, ::isatty(STDERR_FILENO) == 1,
                         &g_interrupted, &std::cin};
  seqc::audio::SndfileAudioReader audio;
  seqc::boards::AudioSongReader songs(audio);
  ctx.stops_cleanly = &g_stops_cleanly;
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

}  // namespace

int main(int argc, char** argv) {
  // A closed terminal (SIGHUP) or a service manager (SIGTERM) stops seqc as Ctrl-C does: at
  // once, or, once a command has a robot, a song or a server running, after it has stopped the
  // robot, ended the song and restored the port.
  struct sigaction sa {};
  sa.sa_handler = on_stop_signal;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
  // Under nohup, SIGHUP arrives ignored and stays so: the run outlives its terminal as asked.
  struct sigaction hup {};
  if (sigaction(SIGHUP, nullptr, &hup) == 0 && hup.sa_handler != SIG_IGN) {
    sigaction(SIGHUP, &sa, nullptr);
  }
  std::signal(SIGPIPE, SIG_IGN);
  int code = seqc::cli::to_int(seqc::cli::ExitCode::Internal);
  try {
    code = run_seqc(argc, argv);
  } catch (const std::bad_alloc&) {
    std::cerr << "seqc: error: out of memory\n";
    return seqc::cli::to_int(seqc::cli::ExitCode::Internal);
  }
  return seqc::cli::exit_status(code, g_signal.load());
}
