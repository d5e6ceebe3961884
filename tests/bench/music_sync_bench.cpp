// music_sync_bench: how close to a song's downbeat as heard a robot starts, through a real sound
// server. Run it under tests/music/with_pulse.sh (which starts PulseAudio with a null sink when
// none is running):
//
//   tests/music/with_pulse.sh build/tests/bench/music_sync_bench [--runs N]
//
// Each run (default 20) plays a 1.2 s song, silence with a click exactly on its downbeat at
// 0.750 s, through PulseAudioOutput, and starts group 0 of an xArm controller emulated at 9600
// baud on a pseudo-terminal with boards::run_on_downbeat, as `seqc upload --run --music` does.
// The null sink's monitor dates the click as it leaves the sink; the emulated controller dates
// GroupRun as its last byte arrives; both on the host's monotonic clock.
//   skew  GroupRun's arrival - the click leaving the sink, ms (positive: the robot is late).
// Printed: every run's skew and seqc's own figure (its write against its plan), then mean, p99
// (nearest rank) and worst |skew|. Target: p99 <= 2 ms. Timings are printed, never judged.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

#include "runtime/audio/pulse_output.hpp"
#include "runtime/boards/music_start.hpp"
#include "runtime/boards/ports.hpp"
#include "tests/music/pulse_harness.hpp"

using namespace seqc;

namespace {

constexpr double kRate = 44100;

double ms(io::Duration d) { return std::chrono::duration<double, std::milli>(d).count(); }

}  // namespace

int main(int argc, char** argv) {
  int runs = 20;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--runs") == 0 && i + 1 < argc) runs = std::atoi(argv[++i]);
  }
  io::SteadyClock clock;
  test::PtyController controller;
  if (!controller.error.empty()) {
    std::fprintf(stderr, "music_sync_bench: %s\n", controller.error.c_str());
    return 2;
  }
  test::SinkKeepAlive keep_alive(kRate);
  test::MonitorRecorder recorder(kRate);
  if (!keep_alive.error.empty() || !recorder.error.empty()) {
    std::fprintf(stderr, "music_sync_bench: %s%s (run it under tests/music/with_pulse.sh)\n",
                 keep_alive.error.c_str(), recorder.error.c_str());
    return 2;
  }
  const boards::Board& board = *boards::find_board("xarm");
  boards::OpenResult opened = boards::open_port({controller.path(), &board}, clock);
  if (!opened.port) {
    std::fprintf(stderr, "music_sync_bench: cannot open %s: %s\n", controller.path().c_str(),
                 opened.failure.detail.c_str());
    return 2;
  }
  const boards::Line line{*opened.port->transport, clock, nullptr, std::chrono::milliseconds(300)};
  audio::PulseAudioOutputFactory speakers(clock, "music_sync_bench");
  const audio::MonoAudio song = test::click_song(kRate, 1.2, 0.75);

  std::vector<double> planned;  // seqc's own: written - planned write, ms
  for (int run = 0; run < runs; ++run) {
    auto output = speakers.open();
    if (!output) {
      std::fprintf(stderr, "music_sync_bench: %s\n", output.error().message.c_str());
      return 2;
    }
    auto started = boards::start_song(**output, song, std::chrono::milliseconds(750));
    if (!started) {
      std::fprintf(stderr, "music_sync_bench: %s\n", started.error().message.c_str());
      return 2;
    }
    const boards::MusicRunReport r =
        boards::run_on_downbeat(board, line, 0, 1, *started, io::Duration{0});
    planned.push_back(r.start.written ? ms(*r.start.written - r.start.plan.write_at) : NAN);
    // Until the click has been recorded (at most 2 s), then the next run.
    const io::TimePoint give_up = clock.now() + std::chrono::seconds(2);
    while (recorder.click_count() < static_cast<std::size_t>(run + 1) && clock.now() < give_up) {
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    (*output)->stop();
    std::this_thread::sleep_for(std::chrono::milliseconds(250));  // silence between clicks
  }
  recorder.stop();
  controller.stop();

  const std::vector<io::TimePoint> clicks = recorder.clicks();
  const std::vector<io::TimePoint> arrivals =
      controller.arrivals(Bytes{0x55, 0x55, 0x05, 0x06, 0x00, 0x01, 0x00});
  if (clicks.size() != static_cast<std::size_t>(runs) ||
      arrivals.size() != static_cast<std::size_t>(runs)) {
    std::fprintf(stderr, "music_sync_bench: %zu clicks and %zu GroupRuns for %d runs\n",
                 clicks.size(), arrivals.size(), runs);
    return 1;
  }
  std::vector<double> skews, magnitudes;
  std::printf("run  skew (ms)  seqc's write vs its plan (ms)\n");
  for (int run = 0; run < runs; ++run) {
    const auto i = static_cast<std::size_t>(run);
    skews.push_back(ms(arrivals[i] - clicks[i]));
    magnitudes.push_back(std::fabs(skews.back()));
    std::printf("%3d  %+9.3f  %+9.3f\n", run + 1, skews.back(), planned[i]);
  }
  double mean = 0;
  for (double s : skews) mean += s;
  mean /= static_cast<double>(skews.size());
  std::sort(magnitudes.begin(), magnitudes.end());
  const auto rank = static_cast<std::size_t>(std::ceil(0.99 * static_cast<double>(runs)));
  const double p99 = magnitudes[std::clamp<std::size_t>(rank, 1, magnitudes.size()) - 1];
  std::printf(
      "start skew over %d runs: mean %+.3f ms, p99 |skew| %.3f ms, worst %.3f ms "
      "(target p99 <= 2 ms)\n",
      runs, mean, p99, magnitudes.back());
  return 0;
}
