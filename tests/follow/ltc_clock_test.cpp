// The LTC show clock on libltc's signals through the WAV input at real-time pace on a manual
// clock (every date exact, an eleven-second show in milliseconds): when it locks, that it keeps
// the offset, freewheels through a one-second dropout, re-locks after a jump and stops two
// seconds after the timecode ends or stands still. The numbers come from the signals'
// layout (ltc_signal.py) by hand: frame k of a file ends at (k + 1) frame lengths.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "runtime/audio/wav_input.hpp"
#include "runtime/follow/ltc_clock.hpp"
#include "tests/follow/ltc_test_signals.hpp"

namespace seqc::follow {
namespace {

double ms(io::TimePoint t) { return static_cast<double>(t.count()) / 1e6; }

std::vector<ShowClockEvent> run(const std::string& name, ltc::Timecode start,
                                io::ManualClock& clock) {
  auto input =
      audio::open_wav_input(testing::ltc_signal_path(name), clock, audio::WavPace::RealTime);
  EXPECT_TRUE(input.ok()) << input.error().message;
  if (!input) return {};
  LtcClockOptions options;
  options.start = start;
  auto ltc = LtcClock::create(std::move(*input), clock, options);
  EXPECT_TRUE(ltc.ok());
  std::vector<ShowClockEvent> events;
  const io::TimePoint never = io::TimePoint{std::chrono::hours(1)};
  while (!(*ltc)->ended() && events.size() < 10000) {
    if (auto e = (*ltc)->next(never)) events.push_back(*e);
  }
  return events;
}

struct Show {
  const char* file;
  int fps;          // frames a second in the label
  double frame_ms;  // a frame's real length
  ltc::Timecode start;
  ltc::Timecode jump_lock;  // the fourth frame after the jump, where it re-locks
  // Frames: the run before the dropout is frames 0 .. 5 fps - 1 (its last unheard), the one
  // after it 6 fps .. 8 fps - 1, the jump 8 fps .. 10 fps - 1 (its last unheard).
};

void expect_show(const Show& show, double jump_dance_ms) {
  SCOPED_TRACE(show.file);
  io::ManualClock clock;
  const std::vector<ShowClockEvent> events = run(show.file, show.start, clock);
  ASSERT_GE(events.size(), 3u);
  const int fps = show.fps;
  const double frame = show.frame_ms;

  // Locked on the fourth frame heard (frame 3), a second before --start.
  EXPECT_EQ(events[0].kind, ShowClockKind::Open);
  EXPECT_NEAR(ms(events[0].at), 4 * frame, 0.05);
  EXPECT_NEAR(events[0].dance_ms, (4 - fps) * frame, 1e-6);
  // Start as frame fps - 1 ends: --start itself.
  EXPECT_EQ(events[1].kind, ShowClockKind::Start);
  EXPECT_NEAR(ms(events[1].at), fps * frame, 0.05);
  EXPECT_EQ(events[1].dance_ms, 0.0);

  std::vector<double> offsets;  // host ms - dance ms, for every Sync before the jump
  std::size_t i = 2;
  for (; i < events.size() && events[i].detail.find("jumped") == std::string::npos; ++i) {
    ASSERT_EQ(events[i].kind, ShowClockKind::Sync) << events[i].detail;
    offsets.push_back(ms(events[i].at) - events[i].dance_ms);
  }
  // Frames fps .. 5 fps - 2 and 6 fps .. 8 fps - 1: through the dropout without a Stop.
  EXPECT_EQ(offsets.size(), static_cast<std::size_t>(4 * fps - 1 + 2 * fps));
  for (double offset : offsets) EXPECT_NEAR(offset, fps * frame, 0.05);
  EXPECT_NEAR(ms(events[2 + 4 * fps - 1].at), (6 * fps + 1) * frame, 0.05);  // back after it

  // The jump: a Sync at the new position once four frames of it are heard.
  ASSERT_LT(i, events.size());
  EXPECT_EQ(events[i].detail, "the timecode jumped to " + ltc::to_text(show.jump_lock));
  EXPECT_NEAR(ms(events[i].at), (8 * fps + 4) * frame, 0.05);
  EXPECT_NEAR(events[i].dance_ms, jump_dance_ms, 1e-6);
  const double jump_offset = ms(events[i].at) - events[i].dance_ms;
  std::size_t syncs_after = 0;
  for (++i; i < events.size() && events[i].kind == ShowClockKind::Sync; ++i, ++syncs_after) {
    EXPECT_NEAR(ms(events[i].at) - events[i].dance_ms, jump_offset, 0.05);
  }
  EXPECT_EQ(syncs_after, static_cast<std::size_t>(2 * fps - 5));

  // Stop two seconds after the last frame heard (frame 10 fps - 2).
  ASSERT_EQ(i + 1, events.size());
  EXPECT_EQ(events[i].kind, ShowClockKind::Stop);
  const double last_frame_end = (10 * fps - 1) * frame;
  EXPECT_NEAR(ms(events[i].at), last_frame_end + 2000, 0.05);
  EXPECT_NEAR(events[i].dance_ms, ms(events[i - 1].at) - jump_offset + 2000, 0.05);
  EXPECT_EQ(events[i].detail.rfind("no timecode since 01:10:01", 0), 0u) << events[i].detail;
  std::printf(
      "[ ltc %s ] locked after %.1f ms (4 frames heard), started at --start %.1f ms, "
      "freewheeled %.1f ms after the last frame before Stop\n",
      show.file, ms(events[0].at), ms(events[1].at), ms(events[i].at) - last_frame_end);
}

TEST(LtcClock, FollowsAShowAt25Fps) {
  // 01:10:00:03 ends 10 min + 160 ms after --start 01:00:00:00.
  expect_show({"ltc-show-25-48000", 25, 40.0, {1, 0, 0, 0, false}, {1, 10, 0, 3, false}}, 600160.0);
}

TEST(LtcClock, FollowsAShowAt2997DropFrame) {
  // 01:10:00;03 is 17982 + 3 frames after 01:00:00;00; it ends one frame later.
  expect_show({"ltc-show-2997df-48000", 30, 1001.0 / 30, {1, 0, 0, 0, true}, {1, 10, 0, 3, true}},
              17986 * 1001.0 / 30);
}

TEST(LtcClock, StopsWhenTheTimecodeStandsStill) {
  io::ManualClock clock;
  const std::vector<ShowClockEvent> events = run("ltc-still-25-48000", {10, 0, 0, 0, false}, clock);
  // Locked past --start at frame 3: Open and Start together, 160 ms in.
  ASSERT_EQ(events.size(), 2u + 46u + 1u);
  EXPECT_EQ(events[0].kind, ShowClockKind::Open);
  EXPECT_EQ(events[1].kind, ShowClockKind::Start);
  EXPECT_NEAR(ms(events[1].at), 160, 0.05);
  EXPECT_EQ(events[1].dance_ms, 160.0);
  EXPECT_EQ(events[1].detail, "locked at 25 fps, timecode 10:00:00:03");
  for (std::size_t i = 2; i < 48; ++i) {
    EXPECT_EQ(events[i].kind, ShowClockKind::Sync);
    EXPECT_NEAR(ms(events[i].at), events[i].dance_ms, 0.05);
  }
  // Frame 49 (10:00:01:24) ends at 2 s; the same label repeats after it.
  EXPECT_EQ(events[48].kind, ShowClockKind::Stop);
  EXPECT_NEAR(ms(events[48].at), 4000, 0.05);
  EXPECT_EQ(events[48].detail, "the timecode stands still at 10:00:01:24");
}

TEST(LtcClock, WaitsForAStartThatComesLater) {
  io::ManualClock clock;
  // --start past the whole signal: locked, never started, no Stop.
  const std::vector<ShowClockEvent> events = run("ltc-25-48000", {11, 0, 0, 0, false}, clock);
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].kind, ShowClockKind::Open);
  EXPECT_EQ(events[0].detail, "locked at 25 fps on 10:00:00:03");
  EXPECT_NEAR(events[0].dance_ms, -3600000.0 + 160, 1e-6);
}

TEST(LtcClock, SaysWhenTheStartNamesNoFrameAtTheRate) {
  io::ManualClock clock;
  const std::vector<ShowClockEvent> events = run("ltc-25-48000", {10, 0, 1, 27, false}, clock);
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].kind, ShowClockKind::Stop);
  EXPECT_EQ(events[0].detail, "--start 10:00:01:27 names no frame at 25 fps");
}

TEST(LtcClock, RefusesAnInputItCannotDecode) {
  io::ManualClock clock;
  class Fast final : public audio::AudioInput {
   public:
    double sample_rate() const override { return 192000; }
    Result<audio::InputBlock> read(std::span<float>) override { return audio::InputBlock{}; }
    std::string describe() const override { return "a 192 kHz input"; }
  };
  auto ltc = LtcClock::create(std::make_unique<Fast>(), clock, {});
  ASSERT_FALSE(ltc.ok());
  EXPECT_EQ(ltc.error().message,
            "a 192 kHz input: timecode is read at 8000-96000 Hz, not 192000 Hz");
}

}  // namespace
}  // namespace seqc::follow
