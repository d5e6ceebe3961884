// `--realtime` on `seqc play`, `seqc upload --run` and `seqc show`, in-process on the emulated
// controller and a manual clock, with a scheduler that stands in for the system's: it grants or
// refuses, and notes what the controller had received each time it was raised and lowered, so
// the tests see which stretch of each command ran under real-time priority. A refusal is a
// warning and the command goes on.
#include <gtest/gtest.h>

#include <chrono>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "runtime/audio/manual_output.hpp"
#include "tests/cli/device_test_util.hpp"
#include "tests/cli/quiet_songs.hpp"
#include "tests/cli/two_beat_song_dance.hpp"

namespace seqc::cli::test {
namespace {

using std::chrono::milliseconds;

// What a refused process is told (EPERM), as request_realtime_scheduling words it, shortened.
constexpr const char* kRefusal = "cannot use real-time scheduling: Operation not permitted";
constexpr const char* kWarning =
    "seqc: warning: cannot use real-time scheduling: Operation not permitted; playing at normal "
    "priority\n";

class NotingScheduler final : public io::Scheduler {
 public:
  NotingScheduler(bool grant, std::function<std::string()> look)
      : grant_(grant), look_(std::move(look)) {}
  Status raise() override {
    raised.push_back(look_());
    if (!grant_) return make_error(kRefusal);
    return Ok{};
  }
  void lower() override { lowered.push_back(look_()); }
  std::vector<std::string> raised;   // what look() said at each raise()
  std::vector<std::string> lowered;  // and at each lower()

 private:
  bool grant_;
  std::function<std::string()> look_;
};

// GroupRun (command 6) frames the controller has received.
std::size_t group_runs(const emu::XArmEmulator& emu) {
  std::size_t n = 0;
  for (const emu::ReceivedFrame& f : emu.received()) {
    if (f.frame && f.frame->cmd == 0x06) ++n;
  }
  return n;
}

// MultiServoMove (command 3) frames the controller has received.
std::size_t moves(const emu::XArmEmulator& emu) {
  std::size_t n = 0;
  for (const emu::ReceivedFrame& f : emu.received()) {
    if (f.frame && f.frame->cmd == 0x03) ++n;
  }
  return n;
}

// The emulated controller at 9600 baud, a manual audio output with 50 ms of latency, and the
// noting scheduler, which says what group 0 and the song were at each raise and lower.
struct RealtimeHarness : DeviceHarness {
  explicit RealtimeHarness(bool grant, std::uint8_t group = 0)
      : DeviceHarness(at_9600()), noting(grant, [this, group] { return look(group); }) {
    audio_files = &songs;
    audio_output = &speakers;
    scheduler = &noting;
    files.add("dance.yaml", kTwoBeatSongDance);
  }
  static emu::XArmConfig at_9600() {
    emu::XArmConfig c;
    c.baud = 9600;
    return c;
  }
  std::string look(std::uint8_t group) const {
    return std::string("group ") + std::to_string(group) +
           (emu.stored_group(group) ? " stored" : " not stored") + ", " +
           std::to_string(group_runs(emu)) + " GroupRun, " + std::to_string(moves(emu)) +
           " moves, song " + song_state();
  }
  // The song is 2 s long: "playing" until 2 s after its start, then "over".
  std::string song_state() const {
    if (speakers.last() == nullptr || !speakers.last()->started_at()) return "not started";
    return clock.now() - *speakers.last()->started_at() < std::chrono::seconds(2) ? "playing"
                                                                                  : "over";
  }
  QuietSongs songs;
  audio::ManualAudioOutputFactory speakers{clock, milliseconds(50)};
  NotingScheduler noting;
};

// When `frame` (hand-written hex) reached the controller, from the song's start, in ms.
std::optional<double> arrival_ms(const RealtimeHarness& h, const std::string& frame) {
  if (h.speakers.last() == nullptr || !h.speakers.last()->started_at()) return std::nullopt;
  for (const emu::ReceivedFrame& f : h.emu.received()) {
    if (to_hex(f.raw) == hex(frame)) {
      return std::chrono::duration<double, std::milli>(f.at - *h.speakers.last()->started_at())
          .count();
    }
  }
  return std::nullopt;
}

// ---- upload --run --music ---------------------------------------------------------------------

TEST(Realtime, UploadRunMusicRaisesFromTheSongsStartToTheGroupsStart) {
  RealtimeHarness h(true);
  const RunResult r =
      h.run({"upload", "dance.yaml", "--port", "emu:xarm", "--run", "--music", "--realtime"});
  ASSERT_EQ(r.code, 0) << r.err;
  // Raised once the group was stored and before the song started; lowered once GroupRun had
  // gone (800 ms into the song), while the song still played.
  EXPECT_EQ(h.noting.raised,
            std::vector<std::string>{"group 0 stored, 0 GroupRun, 0 moves, song not started"});
  EXPECT_EQ(h.noting.lowered,
            std::vector<std::string>{"group 0 stored, 1 GroupRun, 0 moves, song playing"});
  EXPECT_EQ(r.err.find("seqc: warning:"), std::string::npos) << r.err;
}

TEST(Realtime, UploadRunMusicRefusedWarnsAndStartsOnTheDownbeatAnyway) {
  RealtimeHarness h(false);
  const RunResult r =
      h.run({"upload", "dance.yaml", "--port", "emu:xarm", "--run", "--music", "--realtime"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find(kWarning), std::string::npos) << r.err;
  EXPECT_EQ(h.noting.raised.size(), 1u);
  EXPECT_TRUE(h.noting.lowered.empty());  // nothing was raised, so nothing is lowered
  // 50 ms of latency + the downbeat at 750 ms: GroupRun 0 (55 55 05 06 00 01 00) finishes
  // arriving 800 ms after the song's start.
  const auto at = arrival_ms(h, "55 55 05 06 00 01 00");
  ASSERT_TRUE(at.has_value()) << r.err;
  EXPECT_NEAR(*at, 800.0, 1e-5);
}

TEST(Realtime, UploadWithoutItAsksNothing) {
  RealtimeHarness h(false);
  const RunResult r = h.run({"upload", "dance.yaml", "--port", "emu:xarm", "--run", "--music"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(h.noting.raised.empty());
  EXPECT_EQ(r.err.find("seqc: warning:"), std::string::npos) << r.err;
}

// ---- upload without a timed start -------------------------------------------------------------

TEST(Realtime, UploadNeedsRun) {
  RealtimeHarness h(true);
  const RunResult r = h.run({"upload", "dance.yaml", "--port", "emu:xarm", "--realtime"});
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--realtime requires --run"), std::string::npos) << r.err;
  EXPECT_TRUE(h.noting.raised.empty());
  EXPECT_FALSE(h.emu.stored_group(0).has_value());  // nothing was sent
}

TEST(Realtime, APlainRunKeepsNoTimeSoNothingIsRaised) {
  RealtimeHarness h(false);
  const RunResult r = h.run({"upload", "dance.yaml", "--port", "emu:xarm", "--run", "--realtime"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(h.noting.raised.empty());
  EXPECT_EQ(r.err.find("seqc: warning:"), std::string::npos) << r.err;
  EXPECT_EQ(group_runs(h.emu), 1u);
}

// ---- upload --run --resync --------------------------------------------------------------------

TEST(Realtime, ResyncRaisesOverTheStartsAlone) {
  RealtimeHarness h(true, 1);
  // Two bars at 120 bpm in 4/4 (2 s each), cut every bar: groups 0 and 1.
  h.files.add("bars.yaml",
              "robot: xarm\ntempo: 120\nmeter: 4/4\nsequence:\n"
              "  - move: {base: 600}\n    time: 2s\n"
              "  - move: {base: 400}\n    time: 2s\n");
  const RunResult r = h.run({"upload", "bars.yaml", "--port", "emu:xarm", "--run", "--resync", "1",
                             "--force", "--realtime"});
  ASSERT_EQ(r.code, 0) << r.err;
  // Raised once the last piece (group 1) was stored, lowered after both starts.
  EXPECT_EQ(h.noting.raised,
            std::vector<std::string>{"group 1 stored, 0 GroupRun, 0 moves, song not started"});
  EXPECT_EQ(h.noting.lowered,
            std::vector<std::string>{"group 1 stored, 2 GroupRun, 0 moves, song not started"});
}

TEST(Realtime, ResyncRefusedWarnsAndStartsEveryPiece) {
  RealtimeHarness h(false, 1);
  h.files.add("bars.yaml",
              "robot: xarm\ntempo: 120\nmeter: 4/4\nsequence:\n"
              "  - move: {base: 600}\n    time: 2s\n"
              "  - move: {base: 400}\n    time: 2s\n");
  const RunResult r = h.run({"upload", "bars.yaml", "--port", "emu:xarm", "--run", "--resync", "1",
                             "--force", "--realtime"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find(kWarning), std::string::npos) << r.err;
  EXPECT_EQ(group_runs(h.emu), 2u);
}

// ---- play -------------------------------------------------------------------------------------

TEST(Realtime, PlayRefusedWarnsAndPlaysEveryMove) {
  RealtimeHarness h(false);
  const RunResult r = h.run({"play", "dance.yaml", "--port", "emu:xarm", "--force", "--realtime"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find(kWarning), std::string::npos) << r.err;
  // The whole play: asked before anything was sent.
  EXPECT_EQ(h.noting.raised,
            std::vector<std::string>{"group 0 not stored, 0 GroupRun, 0 moves, song not started"});
  EXPECT_EQ(moves(h.emu), 2u);  // base to 400, then to 600
}

TEST(Realtime, PlayGrantedLowersAfterTheLastMove) {
  RealtimeHarness h(true);
  const RunResult r = h.run({"play", "dance.yaml", "--port", "emu:xarm", "--force", "--realtime"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(h.noting.lowered,
            std::vector<std::string>{"group 0 not stored, 0 GroupRun, 2 moves, song not started"});
}

// ---- show -------------------------------------------------------------------------------------

constexpr const char* kSolo =
    "show: solo\nperformers:\n  arm: {file: dance.yaml, port: emu:xarm, "
    "group: 2}\n";

TEST(Realtime, ShowRaisesFromTheSongsStartOverThePerformance) {
  RealtimeHarness h(true, 2);
  h.files.add("solo.yaml", kSolo);
  const RunResult r = h.run({"show", "solo.yaml", "--music", "--realtime"});
  ASSERT_EQ(r.code, 0) << r.err;
  // Raised after the upload, before the song; lowered once GroupRun 2 had gone, while the song
  // still played.
  EXPECT_EQ(h.noting.raised,
            std::vector<std::string>{"group 2 stored, 0 GroupRun, 0 moves, song not started"});
  EXPECT_EQ(h.noting.lowered,
            std::vector<std::string>{"group 2 stored, 1 GroupRun, 0 moves, song playing"});
}

TEST(Realtime, ShowRefusedWarnsAndStarts) {
  RealtimeHarness h(false, 2);
  h.files.add("solo.yaml", kSolo);
  const RunResult r = h.run({"show", "solo.yaml", "--realtime"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find(kWarning), std::string::npos) << r.err;
  EXPECT_EQ(h.noting.raised,
            std::vector<std::string>{"group 2 stored, 0 GroupRun, 0 moves, song not started"});
  EXPECT_EQ(h.emu.playing_group(), std::optional<std::uint8_t>(2));
  // One performer, counted as one.
  EXPECT_NE(r.err.find("seqc: show solo: starting 1 performer at one instant\n"), std::string::npos)
      << r.err;
}

}  // namespace
}  // namespace seqc::cli::test
