// The deadline scheduler on a ManualClock: frames go out at start + at_i exactly (less their own
// wire time when the link has one), a slow write
// or a late wake-up delays only the frames already due, and an interrupt or failed write sends
// the safe stop before play() returns. No test here waits in real time.
#include <gtest/gtest.h>

#include <atomic>
#include <functional>
#include <map>
#include <vector>

#include "runtime/player/player.hpp"

namespace seqc::player {
namespace {

using std::chrono::milliseconds;

// Records each write with the clock's time; can be told to take time over some writes, fail
// one, or raise the interrupt flag once a given write is done.
class FakeLink final : public io::Transport {
 public:
  explicit FakeLink(io::ManualClock& clock) : clock_(clock) {}
  Status write(ByteView bytes) override {
    const std::size_t n = writes.size() + attempts_failed_;
    if (fail_at && *fail_at == n) {
      ++attempts_failed_;
      fail_at.reset();
      return make_error("device went away");
    }
    writes.push_back({clock_.now(), Bytes(bytes.begin(), bytes.end())});
    if (auto it = slow.find(n); it != slow.end()) clock_.advance(it->second);
    if (interrupt_after && *interrupt_after == n && flag != nullptr) flag->store(true);
    return Ok{};
  }
  io::ReadResult read(std::span<std::uint8_t>, io::TimePoint) override { return {}; }
  void discard_input() override {}
  std::string describe() const override { return "fake"; }

  struct Write {
    io::TimePoint at;
    Bytes bytes;
  };
  std::vector<Write> writes;
  std::map<std::size_t, io::Duration> slow;  // write index -> time it takes
  std::optional<std::size_t> fail_at;
  std::optional<std::size_t> interrupt_after;
  std::atomic<bool>* flag = nullptr;

 private:
  io::ManualClock& clock_;
  std::size_t attempts_failed_ = 0;
};

std::vector<ScheduledFrame> schedule(std::initializer_list<int> at_ms) {
  std::vector<ScheduledFrame> out;
  std::uint8_t tag = 0;
  for (int ms : at_ms) out.push_back({milliseconds(ms), Bytes{tag++}});
  return out;
}

const io::TimePoint kStart = milliseconds(5000);
const Bytes kStop{0xff, 0xfe, 0x03, 0x08, 0x01, 0, 0, 0, 0, 0, 0, 0x01, 0x0d};

TEST(Player, SendsEachFrameAtStartPlusItsTime) {
  io::ManualClock clock(kStart);
  FakeLink link(clock);
  const auto frames = schedule({0, 0, 20, 1000, 1500});
  PlayReport r = play(frames, link, clock);
  EXPECT_EQ(r.end, PlayEnd::Completed);
  EXPECT_EQ(r.sent, 5u);
  ASSERT_EQ(link.writes.size(), 5u);
  for (std::size_t i = 0; i < frames.size(); ++i) {
    EXPECT_EQ(link.writes[i].at, kStart + frames[i].at) << i;
    EXPECT_EQ(link.writes[i].bytes, frames[i].bytes);
    EXPECT_EQ(r.lateness[i], io::Duration{0});
  }
  EXPECT_FALSE(r.stop_sent);  // a completed play sends nothing extra
}

// The timing rule: a frame finishes arriving at its time. At 9600 baud (10 bits a byte) a byte
// takes 1/960 s: a 10-byte frame 10.416667 ms, a 25-byte one 26.041667 ms. Frames of 10, 25 and
// 10 bytes at 0, 500 and 1000 ms are written at -10.416667, 473.958333 and 989.583333 ms, so
// each last byte lands at 0, 500 and 1000 ms; the start leaves room for the first one.
TEST(Player, EachFrameFinishesArrivingAtItsTimeWhateverItsSize) {
  io::ManualClock clock(kStart);
  FakeLink link(clock);
  const std::vector<ScheduledFrame> frames{{milliseconds(0), Bytes(10, 0x01)},
                                           {milliseconds(500), Bytes(25, 0x02)},
                                           {milliseconds(1000), Bytes(10, 0x03)}};
  PlayOptions options;
  options.seconds_per_byte = 10.0 / 9600;
  PlayReport r = play(frames, link, clock, options);
  ASSERT_EQ(link.writes.size(), 3u);
  EXPECT_EQ(r.started, kStart + std::chrono::nanoseconds(10'416'667));
  EXPECT_EQ(link.writes[0].at, r.started - std::chrono::nanoseconds(10'416'667));
  EXPECT_EQ(link.writes[1].at, r.started + std::chrono::nanoseconds(473'958'333));
  EXPECT_EQ(link.writes[2].at, r.started + std::chrono::nanoseconds(989'583'333));
  for (io::Duration late : r.lateness) EXPECT_EQ(late, io::Duration{0});
}

// The board's start delay (Track::early) comes on top of each frame's own wire time.
TEST(Player, TheStartDelayIsAddedToEachFramesOwnWireTime) {
  io::ManualClock clock(kStart);
  FakeLink link(clock);
  std::vector<Track> tracks(1);
  tracks[0].transport = &link;
  tracks[0].frames = {{milliseconds(100), Bytes(10, 0x01)}, {milliseconds(200), Bytes(25, 0x02)}};
  tracks[0].seconds_per_byte = 10.0 / 9600;
  tracks[0].early = milliseconds(3);
  PlayOptions options;
  options.start_at = kStart + milliseconds(50);
  PlayReport r = play(tracks, clock, options);
  ASSERT_EQ(link.writes.size(), 2u);
  // 50 + 100 - 3 - 10.416667 and 50 + 200 - 3 - 26.041667 ms after kStart.
  EXPECT_EQ(link.writes[0].at, kStart + std::chrono::nanoseconds(136'583'333));
  EXPECT_EQ(link.writes[1].at, kStart + std::chrono::nanoseconds(220'958'333));
}

// The schedule check uses the same rule: 25-byte frames at 1000 and 1020 ms at 9600 baud. The
// second should start leaving at 1020 - 26.041667 = 993.958333 ms; the first holds the line
// until 1000 ms, so it is 6.041667 ms late, blamed on the first's 26.041667 ms on the wire.
TEST(Player, TheScheduleCheckTimesEachFrameToFinishArriving) {
  const std::vector<ScheduledFrame> frames{{milliseconds(1000), Bytes(25, 0x01)},
                                           {milliseconds(1020), Bytes(25, 0x02)}};
  const ScheduleCheck c = check_schedule(frames, 10.0 / 9600, io::Duration{0});
  ASSERT_TRUE(c.first_late.has_value());
  EXPECT_EQ(*c.first_late, 1u);
  EXPECT_EQ(c.late_by, std::chrono::nanoseconds(6'041'667));
  EXPECT_EQ(c.wire_time, std::chrono::nanoseconds(26'041'667));
  // A 10-byte frame there instead (10.416667 ms, due at 1009.583333 ms) is not late.
  const std::vector<ScheduledFrame> small{{milliseconds(1000), Bytes(25, 0x01)},
                                          {milliseconds(1020), Bytes(10, 0x02)}};
  EXPECT_FALSE(check_schedule(small, 10.0 / 9600, io::Duration{0}).first_late.has_value());
}

TEST(Player, ASlowWriteDelaysOnlyWhatIsAlreadyDue) {
  io::ManualClock clock(kStart);
  FakeLink link(clock);
  link.slow[1] = milliseconds(35);  // the write at 20ms takes until 55ms
  const auto frames = schedule({0, 20, 40, 60, 80, 1000});
  PlayReport r = play(frames, link, clock);
  ASSERT_EQ(link.writes.size(), 6u);
  // 40ms was due during the slow write: sent at 55 (15 late). Every later frame is on time:
  // deadlines are absolute, so the 35ms never carries over.
  const std::vector<int> sent_ms = {0, 20, 55, 60, 80, 1000};
  const std::vector<int> late_ms = {0, 0, 15, 0, 0, 0};
  for (std::size_t i = 0; i < frames.size(); ++i) {
    EXPECT_EQ(link.writes[i].at, kStart + milliseconds(sent_ms[i])) << i;
    EXPECT_EQ(r.lateness[i], milliseconds(late_ms[i])) << i;
  }
  const LatenessSummary s = summarize(r.lateness);
  EXPECT_EQ(s.p50, io::Duration{0});
  EXPECT_EQ(s.max, milliseconds(15));
}

TEST(Player, LatenessDoesNotAccumulateOverManySlowWrites) {
  io::ManualClock clock(kStart);
  FakeLink link(clock);
  std::vector<ScheduledFrame> frames;
  for (int i = 0; i < 1000; ++i) {
    frames.push_back({milliseconds(10 * i), Bytes{1}});
    link.slow[static_cast<std::size_t>(i)] = milliseconds(3);  // every write takes 3 of 10ms
  }
  PlayReport r = play(frames, link, clock);
  ASSERT_EQ(r.sent, 1000u);
  // A relative sleep after each send would end 1000 * 3ms = 3s late; here the last frame is
  // exactly on time.
  EXPECT_EQ(link.writes.back().at, kStart + milliseconds(9990));
  EXPECT_EQ(summarize(r.lateness).max, io::Duration{0});
}

TEST(Player, InterruptSendsTheStopAndSendsNothingElse) {
  io::ManualClock clock(kStart);
  FakeLink link(clock);
  std::atomic<bool> interrupted{false};
  link.flag = &interrupted;
  link.interrupt_after = 1;  // Ctrl-C arrives right after the second frame
  PlayOptions options;
  options.interrupted = &interrupted;
  options.safe_stop = kStop;
  PlayReport r = play(schedule({0, 100, 5000, 9000}), link, clock, options);
  EXPECT_EQ(r.end, PlayEnd::Interrupted);
  EXPECT_EQ(r.sent, 2u);
  EXPECT_TRUE(r.stop_sent);
  ASSERT_EQ(link.writes.size(), 3u);
  EXPECT_EQ(link.writes[2].bytes, kStop);
  // Noticed within one poll interval, not at the next frame's deadline (5s).
  EXPECT_LE(link.writes[2].at - kStart, milliseconds(100) + options.poll_interval);
}

TEST(Player, AnInterruptDuringALongWaitIsNoticedWithinThePollInterval) {
  io::ManualClock clock(kStart);
  std::atomic<bool> interrupted{false};
  PlayOptions options;
  options.interrupted = &interrupted;
  options.safe_stop = kStop;
  options.poll_interval = milliseconds(20);
  // The flag is raised by a clock observer: after 3 slices of waiting.
  int slices = 0;
  class CountingClock final : public io::Clock {
   public:
    CountingClock(io::ManualClock& c, int& n, std::atomic<bool>& f) : c_(c), n_(n), f_(f) {}
    io::TimePoint now() const override { return c_.now(); }
    void sleep_until(io::TimePoint d) override {
      c_.sleep_until(d);
      if (++n_ == 3) f_.store(true);
    }

   private:
    io::ManualClock& c_;
    int& n_;
    std::atomic<bool>& f_;
  } counting(clock, slices, interrupted);
  FakeLink sink(clock);
  PlayReport r = play(schedule({0, 60000}), sink, counting, options);
  EXPECT_EQ(r.end, PlayEnd::Interrupted);
  ASSERT_EQ(sink.writes.size(), 2u);
  EXPECT_EQ(sink.writes[1].bytes, kStop);
  EXPECT_EQ(sink.writes[1].at, kStart + milliseconds(60));
}

TEST(Player, AFailedWriteStillTriesTheStop) {
  io::ManualClock clock(kStart);
  FakeLink link(clock);
  link.fail_at = 2;
  PlayOptions options;
  options.safe_stop = kStop;
  PlayReport r = play(schedule({0, 10, 20, 30}), link, clock, options);
  EXPECT_EQ(r.end, PlayEnd::WriteFailed);
  EXPECT_EQ(r.error, "device went away");
  EXPECT_EQ(r.sent, 2u);
  EXPECT_TRUE(r.stop_sent);
  ASSERT_EQ(link.writes.size(), 3u);
  EXPECT_EQ(link.writes.back().bytes, kStop);
}

TEST(Player, AlreadyInterruptedSendsOnlyTheStop) {
  io::ManualClock clock(kStart);
  FakeLink link(clock);
  std::atomic<bool> interrupted{true};
  PlayOptions options;
  options.interrupted = &interrupted;
  options.safe_stop = kStop;
  PlayReport r = play(schedule({0, 10}), link, clock, options);
  EXPECT_EQ(r.end, PlayEnd::Interrupted);
  EXPECT_EQ(r.sent, 0u);
  ASSERT_EQ(link.writes.size(), 1u);
  EXPECT_EQ(link.writes[0].bytes, kStop);
}

TEST(Player, SummaryUsesNearestRank) {
  std::vector<io::Duration> v;
  for (int i = 1; i <= 200; ++i) v.push_back(milliseconds(i));
  const LatenessSummary s = summarize(v);
  EXPECT_EQ(s.p50, milliseconds(100));
  EXPECT_EQ(s.p99, milliseconds(198));
  EXPECT_EQ(s.max, milliseconds(200));
  EXPECT_EQ(summarize({}).max, io::Duration{0});
}

}  // namespace
}  // namespace seqc::player

namespace seqc::player {
namespace {

// Frames of `size` bytes at the given times (ms).
std::vector<ScheduledFrame> sized(std::size_t size, std::initializer_list<int> at_ms) {
  std::vector<ScheduledFrame> out;
  for (int ms : at_ms) out.push_back({std::chrono::milliseconds(ms), Bytes(size, 0x55)});
  return out;
}

constexpr double k9600 = 10.0 / 9600;  // seconds per byte

double ms(io::Duration d) { return std::chrono::duration<double, std::milli>(d).count(); }

TEST(ScheduleCheck, AMoveDueWhileTheLineIsBusyIsLate) {
  // 25 bytes (a six-servo MultiServoMove) take 25 x 1.0417 ms = 26.04 ms at 9600 baud.
  const ScheduleCheck c = check_schedule(sized(25, {0, 20, 100}), k9600, io::Duration{0});
  ASSERT_TRUE(c.first_late.has_value());
  EXPECT_EQ(*c.first_late, 1u);
  EXPECT_NEAR(ms(c.late_by), 6.04, 0.01);
  EXPECT_NEAR(ms(c.wire_time), 26.04, 0.01);
  EXPECT_EQ(c.late_frames, 1u);
}

TEST(ScheduleCheck, LatenessCarriesOverWhileMovesStayDense) {
  // 20 ms apart, 26.04 ms each: the k-th move starts k x 6.04 ms late.
  const ScheduleCheck c = check_schedule(sized(25, {0, 20, 40, 60}), k9600, io::Duration{0});
  EXPECT_EQ(c.late_frames, 3u);
  EXPECT_NEAR(ms(c.worst), 18.13, 0.01);
}

TEST(ScheduleCheck, ASparseScheduleFits) {
  EXPECT_FALSE(check_schedule(sized(25, {0, 27, 54}), k9600, io::Duration{0}).first_late);
  EXPECT_FALSE(check_schedule(sized(25, {0, 1000}), 0.0, io::Duration{0}).first_late)
      << "an unpaced link keeps any schedule";
}

TEST(ScheduleCheck, HidAllowsOneReportPerInterval) {
  const ScheduleCheck c = check_schedule(sized(25, {0, 0, 5}), 0.0, std::chrono::milliseconds(1));
  ASSERT_TRUE(c.first_late.has_value());
  EXPECT_EQ(*c.first_late, 1u);
  EXPECT_EQ(c.late_by, std::chrono::milliseconds(1));
}

// A link whose bytes leave at 9600 baud: write() returns at once, drain() waits for the line.
class DrainingLink final : public io::Transport {
 public:
  explicit DrainingLink(io::ManualClock& clock) : clock_(clock) {}
  Status write(ByteView bytes) override {
    const io::TimePoint start = std::max(clock_.now(), line_free_);
    line_free_ = start + std::chrono::duration_cast<io::Duration>(std::chrono::duration<double>(
                             static_cast<double>(bytes.size()) * k9600));
    return Ok{};
  }
  Status drain() override {
    ++drains;
    clock_.sleep_until(line_free_);
    return Ok{};
  }
  io::ReadResult read(std::span<std::uint8_t>, io::TimePoint) override { return {}; }
  void discard_input() override {}
  std::string describe() const override { return "draining"; }
  int drains = 0;

 private:
  io::ManualClock& clock_;
  io::TimePoint line_free_{0};
};

TEST(Player, MeasuresLatenessOnceTheBytesHaveLeft) {
  io::ManualClock clock;
  DrainingLink link(clock);
  PlayOptions options;
  options.drain = true;
  options.seconds_per_byte = k9600;
  const PlayReport r = play(sized(25, {0, 20, 100}), link, clock, options);
  ASSERT_EQ(r.end, PlayEnd::Completed);
  EXPECT_EQ(link.drains, 3);
  ASSERT_EQ(r.left_lateness.size(), 3u);
  EXPECT_EQ(r.left_lateness[0], io::Duration{0});
  // Move 2 is written at 26.04 ms (drain of move 1), leaves at 52.08 ms instead of 46.04 ms.
  EXPECT_NEAR(ms(r.left_lateness[1]), 6.04, 0.01);
  EXPECT_EQ(r.left_lateness[2], io::Duration{0});
}

}  // namespace
}  // namespace seqc::player
