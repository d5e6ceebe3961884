// The start of a robot on a song's downbeat as heard (runtime/audio/playback_sync.hpp), worked
// out by hand: every instant below is added up in the comment beside it.
#include <gtest/gtest.h>

#include <chrono>

#include "runtime/audio/manual_output.hpp"
#include "runtime/audio/playback_sync.hpp"

namespace seqc::audio {
namespace {

using std::chrono::milliseconds;
using std::chrono::nanoseconds;
using std::chrono::seconds;

constexpr double k9600 = 10.0 / 9600;  // seconds per byte, 8N1
constexpr double k115200 = 10.0 / 115200;

TEST(PlaybackSync, WireTimeIsTenBitsPerByte) {
  // 7 x 10 / 9600 s = 7.291666... ms, to the nanosecond.
  EXPECT_EQ(wire_time(7, k9600), nanoseconds(7'291'667));
  // 10 x 10 / 115200 s = 0.868055... ms.
  EXPECT_EQ(wire_time(10, k115200), nanoseconds(868'056));
  EXPECT_EQ(wire_time(7, 0), nanoseconds(0));
}

TEST(PlaybackSync, GroupRunIsWrittenSoItArrivesOnTheDownbeatAsHeard) {
  // The audio started at t0 = 1000 s (nothing written yet), the API says 50 ms of latency.
  const io::TimePoint t0 = seconds(1000);
  const PlaybackClock clock{t0, 0, milliseconds(50), 44100};
  StartTiming timing;
  timing.downbeat = milliseconds(750);
  timing.audio_offset = milliseconds(20);
  timing.wire = wire_time(7, k9600);  // GroupRun at 9600 baud: 7.291667 ms
  const StartPlan p = plan_start(clock, timing);
  EXPECT_EQ(p.audio_started, t0);
  EXPECT_EQ(p.latency, milliseconds(50));
  // 50 + 750 + 20 = 820 ms after the start.
  EXPECT_EQ(p.downbeat_heard, t0 + milliseconds(820));
  EXPECT_EQ(p.arrive_at, t0 + milliseconds(820));
  // 820 - 7.291667 = 812.708333 ms.
  EXPECT_EQ(p.write_at, t0 + nanoseconds(812'708'333));
}

TEST(PlaybackSync, TheClockReadLaterDatesTheSameStart) {
  // Read 100 ms into the audio: 4410 frames at 44.1 kHz have gone in, so it started at t0.
  const io::TimePoint t0 = seconds(7);
  const PlaybackClock clock{t0 + milliseconds(100), 4410, milliseconds(30), 44100};
  EXPECT_EQ(clock.started(), t0);
  // 30 ms behind the 4410th frame: 4410 - 0.030 x 44100 = 4410 - 1323.
  EXPECT_EQ(clock.heard_frame(), 3087);
  StartTiming timing;
  timing.downbeat = milliseconds(500);
  timing.audio_offset = milliseconds(-12);  // the speakers are heard earlier than the API says
  timing.wire = wire_time(10, k115200);     // 0.868056 ms
  timing.board_delay = milliseconds(3);
  const StartPlan p = plan_start(clock, timing);
  // 30 + 500 - 12 = 518 ms; arrive 3 ms before it: 515 ms; write 0.868056 ms before that.
  EXPECT_EQ(p.downbeat_heard, t0 + milliseconds(518));
  EXPECT_EQ(p.arrive_at, t0 + milliseconds(515));
  EXPECT_EQ(p.write_at, t0 + milliseconds(515) - nanoseconds(868'056));
}

TEST(PlaybackSync, TheManualOutputPlaysAtItsRateFromItsStart) {
  io::ManualClock clock(seconds(3));
  ManualAudioOutput out(clock, milliseconds(40));
  PcmAudio audio;
  audio.samples.assign(8000, 0.0f);  // 1 s at 8 kHz
  audio.sample_rate = 8000;
  ASSERT_TRUE(out.start(audio).ok());
  clock.advance(milliseconds(250));
  auto c = out.clock();
  ASSERT_TRUE(c.ok());
  EXPECT_EQ(c->written, 2000);  // 0.25 s x 8000
  EXPECT_EQ(c->started(), seconds(3));
  EXPECT_EQ(c->heard_frame(), 2000 - 320);  // 40 ms x 8000 behind
  EXPECT_FALSE(out.finished());
  clock.advance(milliseconds(789));  // 1.039 s: the last sample is heard at 1.040 s
  EXPECT_FALSE(out.finished());
  clock.advance(milliseconds(1));
  EXPECT_TRUE(out.finished());
}

}  // namespace
}  // namespace seqc::audio
