// The player with several tracks on one ManualClock: frames of every track go out at the common
// start + at (less the track's `early`), merged by deadline with ties in track order; `lead` or
// `start_at` moves the start; an early end writes every track's safe stop. No test here waits
// in real time.
#include <gtest/gtest.h>

#include <atomic>
#include <optional>
#include <string>
#include <vector>

#include "runtime/player/player.hpp"

namespace seqc::player {
namespace {

using std::chrono::milliseconds;

// Every write of every link, in order, with the link's name and the clock's time.
struct Log {
  struct Entry {
    std::string link;
    io::TimePoint at;
    Bytes bytes;
  };
  std::vector<Entry> entries;
};

class NamedLink final : public io::Transport {
 public:
  NamedLink(std::string name, io::ManualClock& clock, Log& log)
      : name_(std::move(name)), clock_(clock), log_(log) {}
  Status write(ByteView bytes) override {
    if (fail_next) {
      fail_next = false;
      return make_error("unplugged");
    }
    log_.entries.push_back({name_, clock_.now(), Bytes(bytes.begin(), bytes.end())});
    ++writes;
    if (interrupt_after && *interrupt_after == writes && flag != nullptr) flag->store(true);
    return Ok{};
  }
  io::ReadResult read(std::span<std::uint8_t>, io::TimePoint) override { return {}; }
  void discard_input() override {}
  std::string describe() const override { return name_; }

  bool fail_next = false;
  std::optional<std::size_t> interrupt_after;  // raise the flag after this many writes
  std::atomic<bool>* flag = nullptr;
  std::size_t writes = 0;

 private:
  std::string name_;
  io::ManualClock& clock_;
  Log& log_;
};

Track track(NamedLink& link, std::initializer_list<int> at_ms, std::uint8_t first_tag) {
  Track t;
  t.transport = &link;
  for (int ms : at_ms) t.frames.push_back({milliseconds(ms), Bytes{first_tag++}});
  return t;
}

TEST(PlayerTracks, FramesOfEveryTrackGoOutInDeadlineOrderTiesInTrackOrder) {
  io::ManualClock clock(milliseconds(1000));
  Log log;
  NamedLink a("a", clock, log), b("b", clock, log);
  std::vector<Track> tracks = {track(a, {0, 20, 40}, 0x10), track(b, {10, 20}, 0x20)};
  std::vector<std::pair<std::size_t, std::size_t>> sent;  // (track, index within it)
  PlayOptions options;
  options.on_sent = [&](std::size_t index, const FrameTiming& timing) {
    sent.emplace_back(timing.track, index);
  };
  const PlayReport report = play(tracks, clock, options);

  EXPECT_EQ(report.end, PlayEnd::Completed);
  EXPECT_EQ(report.started, milliseconds(1000));
  ASSERT_EQ(log.entries.size(), 5u);
  const std::vector<std::string> links = {"a", "b", "a", "b", "a"};
  const std::vector<int> at_ms = {1000, 1010, 1020, 1020, 1040};
  const std::vector<std::uint8_t> tags = {0x10, 0x20, 0x11, 0x21, 0x12};
  for (std::size_t i = 0; i < log.entries.size(); ++i) {
    SCOPED_TRACE(i);
    EXPECT_EQ(log.entries[i].link, links[i]);
    EXPECT_EQ(log.entries[i].at, milliseconds(at_ms[i]));
    EXPECT_EQ(log.entries[i].bytes, Bytes{tags[i]});
  }
  const std::vector<std::pair<std::size_t, std::size_t>> expected_sent = {
      {0, 0}, {1, 0}, {0, 1}, {1, 1}, {0, 2}};
  EXPECT_EQ(sent, expected_sent);
  EXPECT_EQ(report.sent, 5u);
  ASSERT_EQ(report.tracks.size(), 2u);
  EXPECT_EQ(report.tracks[0].sent, 3u);
  EXPECT_EQ(report.tracks[1].sent, 2u);
  EXPECT_EQ(report.tracks[0].first, std::optional<io::Duration>(milliseconds(0)));
  EXPECT_EQ(report.tracks[1].first, std::optional<io::Duration>(milliseconds(10)));
  EXPECT_FALSE(report.failed_track.has_value());
}

TEST(PlayerTracks, AnEarlyTrackIsWrittenThatLongBeforeItsTimesFromAGivenStart) {
  io::ManualClock clock(milliseconds(1000));
  Log log;
  NamedLink a("a", clock, log), b("b", clock, log);
  std::vector<Track> tracks = {track(a, {0, 20}, 0x10), track(b, {0, 20}, 0x20)};
  tracks[1].early = milliseconds(7);  // b's frames take 7 ms to arrive
  PlayOptions options;
  options.start_at = milliseconds(1500);  // not now + lead
  const PlayReport report = play(tracks, clock, options);
  EXPECT_EQ(report.started, milliseconds(1500));
  ASSERT_EQ(log.entries.size(), 4u);
  // b at 1500 - 7 = 1493 and 1513; a at 1500 and 1520; merged by when each is written.
  const std::vector<std::string> links = {"b", "a", "b", "a"};
  const std::vector<int> at_ms = {1493, 1500, 1513, 1520};
  for (std::size_t i = 0; i < log.entries.size(); ++i) {
    SCOPED_TRACE(i);
    EXPECT_EQ(log.entries[i].link, links[i]);
    EXPECT_EQ(log.entries[i].at, milliseconds(at_ms[i]));
  }
  EXPECT_EQ(report.tracks[1].first, std::optional<io::Duration>(milliseconds(-7)));
  EXPECT_EQ(report.tracks[1].lateness[0], io::Duration{0});
}

TEST(PlayerTracks, LeadMovesTheCommonStart) {
  io::ManualClock clock(milliseconds(500));
  Log log;
  NamedLink a("a", clock, log), b("b", clock, log);
  std::vector<Track> tracks = {track(a, {0}, 1), track(b, {0, 5}, 2)};
  PlayOptions options;
  options.lead = milliseconds(20);
  const PlayReport report = play(tracks, clock, options);

  EXPECT_EQ(report.started, milliseconds(520));
  ASSERT_EQ(log.entries.size(), 3u);
  EXPECT_EQ(log.entries[0].at, milliseconds(520));
  EXPECT_EQ(log.entries[1].at, milliseconds(520));
  EXPECT_EQ(log.entries[2].at, milliseconds(525));
  EXPECT_EQ(report.tracks[0].first, std::optional<io::Duration>(milliseconds(0)));
  EXPECT_EQ(report.tracks[1].first, std::optional<io::Duration>(milliseconds(0)));
  EXPECT_EQ(report.tracks[1].lateness,
            (std::vector<io::Duration>{milliseconds(0), milliseconds(0)}));
}

TEST(PlayerTracks, AnInterruptWritesEveryTracksSafeStopInTrackOrder) {
  io::ManualClock clock;
  Log log;
  std::atomic<bool> interrupted{false};
  NamedLink a("a", clock, log), b("b", clock, log);
  a.flag = &interrupted;
  a.interrupt_after = 1;
  std::vector<Track> tracks = {track(a, {0, 100}, 1), track(b, {50}, 2)};
  tracks[0].safe_stop = Bytes{0xa0};
  tracks[1].safe_stop = Bytes{0xb0};
  PlayOptions options;
  options.interrupted = &interrupted;
  const PlayReport report = play(tracks, clock, options);

  EXPECT_EQ(report.end, PlayEnd::Interrupted);
  ASSERT_EQ(log.entries.size(), 3u);
  EXPECT_EQ(log.entries[0].bytes, Bytes{1});
  EXPECT_EQ(log.entries[1].link, "a");
  EXPECT_EQ(log.entries[1].bytes, Bytes{0xa0});
  EXPECT_EQ(log.entries[2].link, "b");
  EXPECT_EQ(log.entries[2].bytes, Bytes{0xb0});
  EXPECT_TRUE(report.tracks[0].stop_sent);
  EXPECT_TRUE(report.tracks[1].stop_sent);
  EXPECT_TRUE(report.stop_sent);
  EXPECT_EQ(report.tracks[1].sent, 0u);
  EXPECT_FALSE(report.tracks[1].first.has_value());
}

TEST(PlayerTracks, AFailedWriteStopsTheOtherTracksToo) {
  io::ManualClock clock;
  Log log;
  NamedLink a("a", clock, log), b("b", clock, log);
  std::vector<Track> tracks = {track(a, {0, 100}, 1), track(b, {50}, 2)};
  tracks[0].safe_stop = Bytes{0xa0};
  tracks[1].safe_stop = Bytes{0xb0};
  b.fail_next = true;
  const PlayReport report = play(tracks, clock, PlayOptions{});

  EXPECT_EQ(report.end, PlayEnd::WriteFailed);
  EXPECT_EQ(report.error, "unplugged");
  EXPECT_EQ(report.failed_track, std::optional<std::size_t>(1));
  ASSERT_EQ(log.entries.size(), 3u);
  EXPECT_EQ(log.entries[1].link, "a");
  EXPECT_EQ(log.entries[1].bytes, Bytes{0xa0});
  EXPECT_EQ(log.entries[1].at, milliseconds(50));
  EXPECT_EQ(log.entries[2].link, "b");
  EXPECT_EQ(log.entries[2].bytes, Bytes{0xb0});
  EXPECT_TRUE(report.tracks[0].stop_sent);
  EXPECT_TRUE(report.tracks[1].stop_sent);
}

}  // namespace
}  // namespace seqc::player
