// music_sync_bench: how close to a song's downbeat as heard a robot starts, through a real sound
// server. Run it under tests/music/with_pulse.sh (which starts PulseAudio with a null sink when
// none is running):
//
//   tests/music/with_pulse.sh build/tests/bench/music_sync_bench [--runs N] [--realtime]
//                                                                [--instruments-realtime]
//
// Each run (default 20) plays a 1.2 s song, silence with a click exactly on its downbeat at
// 0.750 s, through PulseAudioOutput, and starts group 0 of an xArm controller emulated at 9600
// baud on a pseudo-terminal with boards::run_on_downbeat, as `seqc upload --run --music` does;
// with --realtime, from the song's start to GroupRun under SCHED_FIFO, as `seqc upload --run
// --music --realtime` does. The emulated controller, the keep-alive stream and the recorder stand
// in for a board and a listener, which have time of their own; on a loaded machine they are
// delayed too and date the click or GroupRun wrongly, so --instruments-realtime starts their
// threads under SCHED_FIFO, and the figures are then about seqc alone.
// The null sink's monitor dates the click as it leaves the sink; the emulated controller dates
// GroupRun as its last byte arrives; both on the host's monotonic clock.
//   skew  GroupRun's arrival - the click leaving the sink, ms (positive: the robot is late).
// Printed: every run's skew and seqc's own figure (its write against its plan), then mean, p99
// (nearest rank) and worst |skew|, and the same of seqc's own figure. Target: p99 <= 2 ms.
// Timings are printed, never judged.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "runtime/audio/pulse_output.hpp"
#include "runtime/boards/music_start.hpp"
#include "runtime/boards/ports.hpp"
#include "runtime/io/realtime.hpp"
#include "tests/music/pulse_harness.hpp"

using namespace seqc;

namespace {

constexpr double kRate = 44100;

double ms(io::Duration d) { return std::chrono::duration<double, std::milli>(d).count(); }

struct Summary {
  double mean = 0;
  double p99 = 0;  // of the magnitudes, nearest rank
  double worst = 0;
};

Summary summarize(const std::vector<double>& values) {
  Summary s;
  std::vector<double> magnitudes;
  for (double v : values) {
    s.mean += v;
    magnitudes.push_back(std::fabs(v));
  }
  s.mean /= static_cast<double>(values.size());
  std::sort(magnitudes.begin(), magnitudes.end());
  const auto rank = static_cast<std::size_t>(std::ceil(0.99 * static_cast<double>(values.size())));
  s.p99 = magnitudes[std::clamp<std::size_t>(rank, 1, magnitudes.size()) - 1];
  s.worst = magnitudes.back();
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  int runs = 20;
  bool realtime = false;
  bool instruments_realtime = false;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--runs") == 0 && i + 1 < argc) runs = std::atoi(argv[++i]);
    if (std::strcmp(argv[i], "--realtime") == 0) realtime = true;
    if (std::strcmp(argv[i], "--instruments-realtime") == 0) instruments_realtime = true;
  }
  io::SteadyClock clock;
  std::optional<test::PtyController> controller_box;
  std::optional<test::SinkKeepAlive> keep_alive_box;
  std::optional<test::MonitorRecorder> recorder_box;
  {
    // Threads inherit their maker's scheduling: the instruments' threads (and their PulseAudio
    // clients') are made while this one is raised, then this one is lowered again.
    const io::RealtimeScope scope(nullptr, instruments_realtime);
    if (!scope.status()) {
      std::fprintf(stderr, "music_sync_bench: %s\n", scope.status().error().message.c_str());
      return 2;
    }
    controller_box.emplace();
    keep_alive_box.emplace(kRate);
    recorder_box.emplace(kRate);
  }
  test::PtyController& controller = *controller_box;
  test::SinkKeepAlive& keep_alive = *keep_alive_box;
  test::MonitorRecorder& recorder = *recorder_box;
  if (!controller.error.empty()) {
    std::fprintf(stderr, "music_sync_bench: %s\n", controller.error.c_str());
    return 2;
  }
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
    std::optional<boards::MusicRunReport> report;
    {
      // The output is open (its threads made) before, as in `seqc upload`.
      const io::RealtimeScope scope(nullptr, realtime);
      if (!scope.status()) {
        std::fprintf(stderr, "music_sync_bench: %s\n", scope.status().error().message.c_str());
        return 2;
      }
      auto started = boards::start_song(**output, song, std::chrono::milliseconds(750));
      if (!started) {
        std::fprintf(stderr, "music_sync_bench: %s\n", started.error().message.c_str());
        return 2;
      }
      report = boards::run_on_downbeat(board, line, 0, 1, *started, io::Duration{0});
    }
    const boards::MusicRunReport& r = *report;
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
  std::vector<double> skews;
  std::printf("run  skew (ms)  seqc's write vs its plan (ms)\n");
  for (int run = 0; run < runs; ++run) {
    const auto i = static_cast<std::size_t>(run);
    skews.push_back(ms(arrivals[i] - clicks[i]));
    std::printf("%3d  %+9.3f  %+9.3f\n", run + 1, skews.back(), planned[i]);
  }
  const Summary skew = summarize(skews);
  std::printf(
      "start skew over %d runs%s%s: mean %+.3f ms, p99 |skew| %.3f ms, worst %.3f ms "
      "(target p99 <= 2 ms)\n",
      runs, realtime ? " (--realtime)" : "",
      instruments_realtime ? " (--instruments-realtime)" : "", skew.mean, skew.p99, skew.worst);
  const Summary write = summarize(planned);
  std::printf("seqc's write vs its plan: mean %+.3f ms, p99 %.3f ms, worst %.3f ms\n", write.mean,
              write.p99, write.worst);
  return 0;
}
