// `seqc upload FILE --run --music` through a real sound server (tests/music/with_pulse.sh starts
// one with a null sink when none runs) to an xArm controller emulated at 9600 baud on a
// pseudo-terminal. The song is silence with a click exactly on its downbeat; the null sink's
// monitor dates the click as it leaves the sink, the emulated controller dates GroupRun as its
// last byte arrives, both on the host's monotonic clock, and the two must agree. The bound is
// loose (a busy machine and the sound server's block size move both by a few milliseconds); it
// is there to catch a start that forgets the latency, the downbeat, the offset or the wire time
// (each 7 ms or more). tests/bench/music_sync_bench measures the skew itself.
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "runtime/audio/pulse_output.hpp"
#include "runtime/audio/sndfile_audio.hpp"
#include "runtime/cli/app.hpp"
#include "runtime/cli/context.hpp"
#include "runtime/io/disk.hpp"
#include "tests/music/pulse_harness.hpp"

namespace seqc::test {
namespace {

namespace fs = std::filesystem;
using std::chrono::milliseconds;

constexpr double kRate = 44100;

struct Run {
  int code = -1;
  std::string err;
};

Run run_seqc(std::vector<std::string> args) {
  args.insert(args.begin(), "seqc");
  std::vector<const char*> argv;
  for (const std::string& a : args) argv.push_back(a.c_str());
  std::ostringstream out, err;
  io::SteadyClock clock;
  io::DiskFileReader files;
  std::atomic<bool> interrupted{false};
  cli::Context ctx{out, err, clock, files, false, &interrupted};
  audio::SndfileAudioReader reader;
  audio::PulseAudioOutputFactory speakers(clock, "seqc-test");
  ctx.audio_files = &reader;
  ctx.audio_output = &speakers;
  Run r;
  r.code = cli::run(static_cast<int>(argv.size()), argv.data(), ctx);
  r.err = err.str();
  return r;
}

// Writes the song (a click on its downbeat) and a choreography dancing to it.
fs::path write_files(double downbeat_s) {
  const fs::path dir =
      fs::path(SEQC_BINARY_DIR) / "tests/music/tmp" / ("pulse-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  audio::SndfileAudioWriter writer;
  EXPECT_TRUE(
      writer.write_wav((dir / "click.wav").string(), click_song(kRate, 1.6, downbeat_s)).ok());
  std::ofstream(dir / "dance.yaml") << "robot: xarm\n"
                                       "music:\n"
                                       "  file: click.wav\n"
                                       "  downbeat: "
                                    << downbeat_s
                                    << "s\n"
                                       "  tempo: 120\n"
                                       "  meter: 4/4\n"
                                       "sequence:\n"
                                       "  - move: {base: 400}\n"
                                       "    time: 1b\n"
                                       "  - move: {base: 600}\n"
                                       "    time: 1b\n";
  return dir;
}

void expect_on_the_downbeat(double downbeat_s, const std::string& offset_ms, double offset_s) {
  const fs::path dir = write_files(downbeat_s);
  PtyController controller;
  ASSERT_TRUE(controller.error.empty()) << controller.error;
  SinkKeepAlive keep_alive(kRate);
  ASSERT_TRUE(keep_alive.error.empty()) << keep_alive.error;
  MonitorRecorder recorder(kRate);
  ASSERT_TRUE(recorder.error.empty()) << recorder.error;
  std::vector<std::string> args{
      "upload", (dir / "dance.yaml").string(), "--port", controller.path(), "--run", "--music"};
  if (!offset_ms.empty()) args.push_back("--audio-offset=" + offset_ms);
  const Run r = run_seqc(args);
  recorder.stop();
  controller.stop();
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("seqc: music: downbeat heard at +"), std::string::npos) << r.err;
  // GroupRun 0 once: 55 55 05 06 00 01 00.
  const auto run = controller.arrival(Bytes{0x55, 0x55, 0x05, 0x06, 0x00, 0x01, 0x00});
  ASSERT_TRUE(run.has_value()) << r.err;
  const std::vector<io::TimePoint> clicks = recorder.clicks();
  ASSERT_EQ(clicks.size(), 1u) << r.err;
  // The robot starts `offset` after the click leaves the sink (the offset is what the speakers
  // add after it).
  const double skew_ms =
      std::chrono::duration<double, std::milli>(*run - clicks[0]).count() - offset_s * 1000;
  std::printf(
      "downbeat %.3f s, offset %s ms: GroupRun arrived %.2f ms after the click left the "
      "sink\n%s",
      downbeat_s, offset_ms.empty() ? "0" : offset_ms.c_str(), skew_ms, r.err.c_str());
  EXPECT_LT(std::abs(skew_ms), 5.0) << r.err;
  fs::remove_all(dir);
}

TEST(PulseSync, GroupRunArrivesAsTheDownbeatLeavesTheSink) { expect_on_the_downbeat(0.75, "", 0); }

TEST(PulseSync, AnEarlyDownbeatAndAnAudioOffset) {
  // 0.1 s is sooner than the output can settle: seqc plays silence first; the speakers are said
  // to be 30 ms late, so the robot starts 30 ms after the click leaves the sink.
  expect_on_the_downbeat(0.1, "30", 0.030);
}

}  // namespace
}  // namespace seqc::test
