// A stored group started on a song's downbeat as heard (runtime/boards/music_start.hpp), on one
// manual clock shared by the audio output and the emulated xArm controller (9600 baud), so the
// instant GroupRun's last byte reaches the controller is exact. Every instant is worked out by
// hand in the comment beside it.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <optional>
#include <string>

#include "runtime/audio/manual_output.hpp"
#include "runtime/boards/music_start.hpp"
#include "runtime/boards/ports.hpp"

namespace seqc::boards {
namespace {

using std::chrono::milliseconds;
using std::chrono::nanoseconds;
using std::chrono::seconds;

emu::XArmConfig paced() {
  emu::XArmConfig c;
  c.baud = 9600;
  return c;
}

struct Stage {
  io::ManualClock clock{seconds(5)};
  emu::XArmEmulator controller{paced()};
  OpenedPort port;
  audio::ManualAudioOutput output{clock, milliseconds(50)};
  audio::MonoAudio song;

  Stage() {
    OpenResult a = open_port({"emu:xarm", find_board("xarm")}, clock,
                             Hooks{&controller, nullptr, &clock, nullptr});
    EXPECT_TRUE(a.port.has_value());
    port = std::move(*a.port);
    song.samples.assign(16000, 0.25f);  // 2 s at 8 kHz
    song.sample_rate = 8000;
  }
  Line line(const std::atomic<bool>* interrupted = nullptr) {
    return Line{*port.transport, *port.clock, interrupted, milliseconds(200)};
  }
  // When GroupRun's last byte reached the controller.
  std::optional<io::TimePoint> group_run_arrival(const std::string& hex) const {
    for (const emu::ReceivedFrame& f : controller.received()) {
      if (to_hex(f.raw) == hex) return f.at;
    }
    return std::nullopt;
  }
};

TEST(MusicStart, GroupRunFinishesArrivingOnTheDownbeatAsHeard) {
  Stage s;
  const io::TimePoint t0 = s.clock.now();  // the song starts now: 5 s
  auto started = start_song(s.output, s.song, milliseconds(750));
  ASSERT_TRUE(started.ok()) << started.error().message;
  EXPECT_EQ(started->lead_in, io::Duration{0});
  EXPECT_EQ(started->downbeat, milliseconds(750));
  const MusicRunReport r =
      run_on_downbeat(*find_board("xarm"), s.line(), 2, 1, *started, milliseconds(20));
  ASSERT_EQ(r.play.end, player::PlayEnd::Completed);
  // Heard at 50 (latency) + 750 (downbeat) + 20 (offset) = 820 ms after the song's start.
  EXPECT_EQ(r.start.plan.downbeat_heard, t0 + milliseconds(820));
  // GroupRun, 7 bytes at 9600 baud, is 7.291667 ms on the wire: written at 812.708333 ms.
  ASSERT_TRUE(r.start.written.has_value());
  EXPECT_EQ(*r.start.written, t0 + nanoseconds(812'708'333));
  EXPECT_EQ(r.start.plan.write_at, t0 + nanoseconds(812'708'333));
  // The emulated controller took GroupRun 2 at 820 ms (its line rounds each byte to the
  // nanosecond).
  const auto arrival = s.group_run_arrival("55 55 05 06 02 01 00");
  ASSERT_TRUE(arrival.has_value());
  const double arrived_ms = std::chrono::duration<double, std::milli>(*arrival - t0).count();
  EXPECT_NEAR(arrived_ms, 820.0, 1e-5);
  EXPECT_LT(std::chrono::abs(r.start.skew), nanoseconds(10));
}

TEST(MusicStart, AnEarlyDownbeatGetsALeadInOfSilence) {
  Stage s;
  const io::TimePoint t0 = s.clock.now();
  // A downbeat 0.2 s into the song is too soon: 0.3 s of silence go first (2400 samples at 8 kHz).
  auto started = start_song(s.output, s.song, milliseconds(200));
  ASSERT_TRUE(started.ok());
  EXPECT_EQ(started->lead_in, milliseconds(300));
  EXPECT_EQ(started->downbeat, milliseconds(500));
  const audio::PcmAudio& played = s.output.played();
  ASSERT_EQ(played.samples.size(), 2400u + 16000u);
  EXPECT_EQ(played.samples[2399], 0.0f);
  EXPECT_EQ(played.samples[2400], 0.25f);
  const MusicRunReport r =
      run_on_downbeat(*find_board("xarm"), s.line(), 0, 1, *started, io::Duration{0});
  ASSERT_EQ(r.play.end, player::PlayEnd::Completed);
  // 50 + 500 = 550 ms; written 7.291667 ms before.
  EXPECT_EQ(r.start.plan.downbeat_heard, t0 + milliseconds(550));
  EXPECT_EQ(*r.start.written, t0 + nanoseconds(542'708'333));
}

TEST(MusicStart, CtrlCBeforeTheDownbeatSendsTheStopInsteadOfTheRun) {
  Stage s;
  auto started = start_song(s.output, s.song, milliseconds(750));
  ASSERT_TRUE(started.ok());
  std::atomic<bool> interrupted{true};
  const MusicRunReport r =
      run_on_downbeat(*find_board("xarm"), s.line(&interrupted), 2, 1, *started, {});
  EXPECT_EQ(r.play.end, player::PlayEnd::Interrupted);
  EXPECT_FALSE(r.start.written.has_value());
  EXPECT_FALSE(r.run.has_value());
  EXPECT_EQ(to_hex(s.controller.received_bytes()), "55 55 02 07");  // GroupStop only
}

TEST(MusicStart, WaitingForTheSongEndsWithItOrWithCtrlC) {
  Stage s;
  auto started = start_song(s.output, s.song, milliseconds(750));
  ASSERT_TRUE(started.ok());
  const io::TimePoint t0 = s.clock.now();
  EXPECT_TRUE(wait_for_song(s.output, s.clock, nullptr));
  // 2 s of song heard 50 ms late: done 2.05 s after its start, within one 20 ms poll.
  EXPECT_GE(s.clock.now() - t0, milliseconds(2050));
  EXPECT_LT(s.clock.now() - t0, milliseconds(2070));
  Stage again;
  ASSERT_TRUE(start_song(again.output, again.song, milliseconds(750)).ok());
  std::atomic<bool> interrupted{true};
  EXPECT_FALSE(wait_for_song(again.output, again.clock, &interrupted));
}

// A downbeat dated on the host's clock, 750 ms ahead of its now, is 750 ms ahead of an
// emulator's own clock too, whatever that clock reads; on one clock it is the same instant.
TEST(MusicStart, ADownbeatIsCarriedOverToAnEmulatorsOwnClock) {
  io::ManualClock host(std::chrono::seconds(21216));
  io::ManualClock emulator(std::chrono::milliseconds(20));
  const io::TimePoint downbeat = host.now() + std::chrono::milliseconds(750);
  EXPECT_EQ(carried_over(downbeat, host, emulator), io::TimePoint(std::chrono::milliseconds(770)));
  EXPECT_EQ(carried_over(downbeat, host, host), downbeat);
}

}  // namespace
}  // namespace seqc::boards
