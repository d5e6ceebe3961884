// `seqc upload --run --music` and `seqc play --music` in-process: the emulated xArm controller
// at 9600 baud and a manual audio output (50 ms of latency) on one manual clock, so the instant
// the start command's last byte reaches the controller is exact. Every instant is worked out by
// hand in the comment beside it.
#include <gtest/gtest.h>

#include <chrono>
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

emu::XArmConfig at_9600() {
  emu::XArmConfig c;
  c.baud = 9600;
  return c;
}

struct MusicHarness : DeviceHarness {
  MusicHarness() : DeviceHarness(at_9600()) {
    audio_files = &songs;
    audio_output = &speakers;
    files.add("dance.yaml", kTwoBeatSongDance);
  }
  // When the frame `hex` reached the controller, from the song's start.
  std::optional<double> arrival_ms(const std::string& frame) const {
    const ManualStart start = speakers.last() ? speakers.last()->started_at() : std::nullopt;
    if (!start) return std::nullopt;
    for (const emu::ReceivedFrame& f : emu.received()) {
      if (to_hex(f.raw) == hex(frame)) {
        return std::chrono::duration<double, std::milli>(f.at - *start).count();
      }
    }
    return std::nullopt;
  }
  using ManualStart = std::optional<io::TimePoint>;
  QuietSongs songs;
  audio::ManualAudioOutputFactory speakers{clock, milliseconds(50)};
};

TEST(DeviceMusic, UploadRunStartsTheGroupOnTheDownbeatAsHeard) {
  MusicHarness h;
  const RunResult r = h.run(
      {"upload", "dance.yaml", "--port", "emu:xarm", "--run", "--music", "--audio-offset", "20"});
  ASSERT_EQ(r.code, 0) << r.err;
  ASSERT_EQ(h.songs.asked.size(), 1u);
  EXPECT_EQ(h.songs.asked[0], "song.wav");
  // 50 ms of latency + the downbeat at 750 ms + 20 ms of offset = 820 ms after the song's start:
  // GroupRun 0 (7 bytes, 7.291667 ms at 9600 baud) finishes arriving then.
  const auto at = h.arrival_ms("55 55 05 06 00 01 00");
  ASSERT_TRUE(at.has_value()) << r.err;
  EXPECT_NEAR(*at, 820.0, 1e-5);
  EXPECT_NE(r.err.find("seqc: music: downbeat heard at +0.820 s (output latency 50.0 ms, "
                       "--audio-offset 20 ms); robot started on it (GroupRun "
                       "written 0.00 ms after its time, 7.29 ms on the wire)"),
            std::string::npos)
      << r.err;
  // The song played to its end (2 s + 50 ms) and its output was stopped.
  ASSERT_NE(h.speakers.last(), nullptr);
  EXPECT_TRUE(h.speakers.last()->stopped());
  EXPECT_GE(h.clock.now() - *h.speakers.last()->started_at(), milliseconds(2050));
}

TEST(DeviceMusic, PlayStartsTheFirstMoveOnTheDownbeatAsHeard) {
  MusicHarness h;
  const RunResult r = h.run({"play", "dance.yaml", "--port", "emu:xarm", "--music", "--force"});
  ASSERT_EQ(r.code, 0) << r.err;
  // The first move: MultiServoMove, 1 servo, 500 ms (1 beat at 120), base (id 6) to 400:
  // 55 55 08 03 01 f4 01 06 90 01, 10 bytes (10.416667 ms on the wire). It finishes arriving
  // 50 + 750 = 800 ms after the song's start.
  const auto at = h.arrival_ms("55 55 08 03 01 f4 01 06 90 01");
  ASSERT_TRUE(at.has_value()) << r.err;
  EXPECT_NEAR(*at, 800.0, 1e-5);
  EXPECT_NE(r.err.find("seqc: music: downbeat heard at +0.800 s (output latency 50.0 ms); robot "
                       "started on it"),
            std::string::npos)
      << r.err;
}

// Every move, whatever its size, finishes arriving on its beat: the second move carries three
// servos, 55 55 0e 03 03 f4 01 + 3 x (id, lo, hi) = 16 bytes, 16.666667 ms on the wire; the
// first is 10 bytes. Beat 2 is heard 50 + 750 + 500 = 1300 ms after the song's start. (Timed by
// its first byte, as the first move is, it would land 6.25 ms late.)
TEST(DeviceMusic, PlayLandsEveryMoveOnItsBeatWhateverItsSize) {
  MusicHarness h;
  h.files.add("dance.yaml",
              "robot: xarm\nmusic:\n  file: song.wav\n  downbeat: 0.750s\n  tempo: 120\n"
              "  meter: 4/4\nsequence:\n  - move: {base: 400}\n    time: 1b\n"
              "  - move: {base: 600, elbow: 300, shoulder: 700}\n    time: 1b\n");
  const RunResult r = h.run({"play", "dance.yaml", "--port", "emu:xarm", "--music", "--force"});
  ASSERT_EQ(r.code, 0) << r.err;
  const auto first = h.arrival_ms("55 55 08 03 01 f4 01 06 90 01");
  ASSERT_TRUE(first.has_value()) << r.err;
  EXPECT_NEAR(*first, 800.0, 1e-5);
  // elbow (4) to 300 = 2c 01, shoulder (5) to 700 = bc 02, base (6) to 600 = 58 02.
  const auto second = h.arrival_ms("55 55 0e 03 03 f4 01 04 2c 01 05 bc 02 06 58 02");
  ASSERT_TRUE(second.has_value()) << r.err;
  EXPECT_NEAR(*second, 1300.0, 1e-4);  // the emulator times each byte to the nanosecond
  EXPECT_NE(r.err.find("late by p50 0.0 ms, p99 0.0 ms, max 0.0 ms"), std::string::npos) << r.err;
}

TEST(DeviceMusic, UploadRunTakesTheRigFilesAudioOffset) {
  MusicHarness h;
  h.files.add("rig.yaml", "audio_offset: 20ms\n");
  RunResult r = h.run(
      {"upload", "dance.yaml", "--port", "emu:xarm", "--run", "--music", "--rig", "rig.yaml"});
  ASSERT_EQ(r.code, 0) << r.err;
  // 50 ms of latency + the downbeat at 750 ms + the rig's 20 ms = 820 ms after the song's start.
  auto at = h.arrival_ms("55 55 05 06 00 01 00");
  ASSERT_TRUE(at.has_value()) << r.err;
  EXPECT_NEAR(*at, 820.0, 1e-5);
  EXPECT_NE(r.err.find("seqc: music: downbeat heard at +0.820 s (output latency 50.0 ms, "
                       "audio_offset 20 ms from rig.yaml); robot started on it"),
            std::string::npos)
      << r.err;

  // --audio-offset wins over the rig's: 50 + 750 + 5 = 805 ms.
  MusicHarness both;
  both.files.add("rig.yaml", "audio_offset: 40ms\n");
  r = both.run({"upload", "dance.yaml", "--port", "emu:xarm", "--run", "--music", "--rig",
                "rig.yaml", "--audio-offset", "5"});
  ASSERT_EQ(r.code, 0) << r.err;
  at = both.arrival_ms("55 55 05 06 00 01 00");
  ASSERT_TRUE(at.has_value()) << r.err;
  EXPECT_NEAR(*at, 805.0, 1e-5);
  EXPECT_NE(r.err.find("(output latency 50.0 ms, --audio-offset 5 ms)"), std::string::npos)
      << r.err;
}

TEST(DeviceMusic, PlayTakesTheRigFilesAudioOffset) {
  MusicHarness h;
  h.files.add("rig.yaml", "clock_ppm: 8000\naudio_offset: -0.01s\n");
  const RunResult r = h.run(
      {"play", "dance.yaml", "--port", "emu:xarm", "--music", "--force", "--rig", "rig.yaml"});
  ASSERT_EQ(r.code, 0) << r.err;
  // The first move finishes arriving 50 + 750 - 10 = 790 ms after the song's start.
  const auto at = h.arrival_ms("55 55 08 03 01 f4 01 06 90 01");
  ASSERT_TRUE(at.has_value()) << r.err;
  EXPECT_NEAR(*at, 790.0, 1e-5);
  EXPECT_NE(r.err.find("audio_offset -10 ms from rig.yaml"), std::string::npos) << r.err;
}

// Without the harness's emulator, `--port emu:xarm` is a fresh one on a clock of its own, as on
// the command line: the song is dated on the host's clock (here the harness's) and the start on
// the emulator's, so the report says no skew is measured instead of "robot started on it".
// The downbeat is still heard 50 ms of latency + 750 ms after the song's start.
RunResult run_on_own_emulator(MusicHarness& h, std::vector<std::string> args) {
  return run_seqc(std::move(args), h.clock, h.files, [&h](Context& ctx) {
    ctx.interrupted = &h.interrupted;
    ctx.audio_files = &h.songs;
    ctx.audio_output = &h.speakers;
  });
}

TEST(DeviceMusic, AnEmulatorInItsOwnTimeGetsNoMeasuredStart) {
  MusicHarness h;
  RunResult r =
      run_on_own_emulator(h, {"upload", "dance.yaml", "--port", "emu:xarm", "--run", "--music"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("seqc: music: downbeat heard at +0.800 s (output latency 50.0 ms); "
                       "GroupRun went to the in-process emulator, which keeps no real time: no "
                       "start skew is measured\n"
                       "seqc: group 0 started in emulated time; the controller reported it "
                       "started; playing the song to its end (Ctrl-C stops both)\n"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(r.err.find("robot started"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("on the downbeat"), std::string::npos) << r.err;
  EXPECT_TRUE(h.speakers.last()->stopped());

  r = run_on_own_emulator(h, {"play", "dance.yaml", "--port", "emu:xarm", "--music", "--force"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("seqc: music: downbeat heard at +0.800 s (output latency 50.0 ms); the "
                       "first move went to the in-process emulator, which keeps no real time: no "
                       "start skew is measured\n"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(r.err.find("robot started"), std::string::npos) << r.err;
}

TEST(DeviceMusic, QuietStillStartsTheGroupOnTheDownbeat) {
  MusicHarness h;
  const RunResult r =
      h.run({"-q", "upload", "dance.yaml", "--port", "emu:xarm", "--run", "--music"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  // 50 ms of latency + 750 ms: GroupRun 0 finishes arriving 800 ms after the song's start.
  const auto at = h.arrival_ms("55 55 05 06 00 01 00");
  ASSERT_TRUE(at.has_value());
  EXPECT_NEAR(*at, 800.0, 1e-5);
}

TEST(DeviceMusic, NoSoundServerIsAnErrorBeforeAnythingIsSent) {
  MusicHarness h;
  h.speakers.fail_open("cannot connect to the sound server: Connection refused");
  const RunResult r = h.run({"upload", "dance.yaml", "--port", "emu:xarm", "--run", "--music"});
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_NE(r.err.find("seqc: error: --music: cannot connect to the sound server: Connection "
                       "refused; nothing was sent"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(h.received(), "");
}

TEST(DeviceMusic, AFileWithoutMusicHasNoSongToPlay) {
  MusicHarness h;
  h.files.add("plain.yaml", "robot: xarm\nsequence:\n  - move: {base: 400}\n    time: 1s\n");
  const RunResult r = h.run({"upload", "plain.yaml", "--port", "emu:xarm", "--run", "--music"});
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("seqc: error: --music: plain.yaml has no `music:` block"), std::string::npos)
      << r.err;
  EXPECT_EQ(h.received(), "");
}

TEST(DeviceMusic, MusicNeedsRunOnUpload) {
  MusicHarness h;
  const RunResult r = h.run({"upload", "dance.yaml", "--port", "emu:xarm", "--music"});
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_EQ(h.received(), "");
}

// --resync with --music: the song's downbeat as heard anchors the first piece's start, and every
// later start is on the same clock at its bar line after it. Two bars at 120 bpm in 4/4 (2 s
// each), cut every bar: groups 0 and 1. Each start is one write of GroupStop (55 55 02 07) and
// GroupRun; it finishes arriving when its time comes.
TEST(DeviceMusic, ResyncStartsTheFirstPieceOnTheDownbeatAndTheRestOnItsClock) {
  MusicHarness h;
  h.files.add("bars.yaml",
              "robot: xarm\nmusic:\n  file: song.wav\n  downbeat: 0.750s\n  tempo: 120\n"
              "  meter: 4/4\nsequence:\n  - move: {base: 600}\n    time: 1bar\n"
              "  - move: {base: 400}\n    time: 1bar\n");
  const RunResult r = h.run({"upload", "bars.yaml", "--port", "emu:xarm", "--run", "--resync", "1",
                             "--music", "--force", "--audio-offset", "20"});
  ASSERT_EQ(r.code, 0) << r.err;
  // 50 ms of latency + the downbeat at 750 ms + 20 ms of offset = 820 ms after the song's start:
  // GroupRun 0 finishes arriving then, and GroupRun 1 one bar (2000 ms) later.
  const auto first = h.arrival_ms("55 55 05 06 00 01 00");
  const auto second = h.arrival_ms("55 55 05 06 01 01 00");
  ASSERT_TRUE(first.has_value() && second.has_value()) << r.err;
  EXPECT_NEAR(*first, 820.0, 1e-5);
  EXPECT_NEAR(*second, 2820.0, 1e-5);
  // The start is 11 bytes at 9600 baud: 11.458333 ms on the wire.
  EXPECT_NE(r.err.find("seqc: music: downbeat heard at +0.820 s (output latency 50.0 ms, "
                       "--audio-offset 20 ms); robot started on it (GroupRun written 0.00 ms "
                       "after its time, 11.46 ms on the wire)\n"
                       "seqc: stored 2 pieces of 1 bar in groups 0-1 and started each at its bar "
                       "line"),
            std::string::npos)
      << r.err;
  ASSERT_NE(h.speakers.last(), nullptr);
  EXPECT_TRUE(h.speakers.last()->stopped());
}

// A dance of 3,000 actions, more than one group holds (1,020): `upload --run --music` stores it
// in groups 0, 1 and 2, each ending on the last bar line it can hold, and starts each on its bar
// line on the song's clock. 3,000 one-beat moves at 120 bpm in 4/4 are 4 actions a bar: group 0
// holds bars 1-255 (1,020 actions), group 1 bars 256-510 from 255 x 2 s = 510 s, group 2 the
// 240 bars left (960 actions) from 1,020 s.
TEST(DeviceMusic, AThreeThousandActionDanceIsChainedOnBarLinesWithTheSong) {
  MusicHarness h;
  h.files.add("long.yaml",
              "robot: xarm\nmusic:\n  file: song.wav\n  downbeat: 0.750s\n  tempo: 120\n"
              "  meter: 4/4\nsequence:\n  - repeat: 1500\n    do:\n"
              "      - move: {base: 300}\n        time: 1b\n"
              "      - move: {base: 700}\n        time: 1b\n");
  const RunResult r = h.run({"upload", "long.yaml", "--port", "emu:xarm", "--run", "--music",
                             "--force", "--audio-offset", "20"});
  ASSERT_EQ(r.code, 0) << r.err;
  const std::size_t sizes[3] = {1020, 1020, 960};
  for (std::uint8_t g = 0; g < 3; ++g) {
    SCOPED_TRACE(g);
    const auto stored = h.emu.stored_group(g);
    ASSERT_TRUE(stored.has_value());
    ASSERT_EQ(stored->size(), sizes[g]);
    // Every action one beat (500 ms), the first of each group base (id 6) to 300.
    EXPECT_EQ(stored->front().time_ms, 500u);
    ASSERT_EQ(stored->front().servos.size(), 1u);
    EXPECT_EQ(stored->front().servos[0].id, 6u);
    EXPECT_EQ(stored->front().servos[0].position, 300u);
  }
  EXPECT_FALSE(h.emu.stored_group(3).has_value());
  // Starts (GroupStop and GroupRun in one write) finish arriving at 820 ms after the song's
  // start (50 ms latency + 750 ms downbeat + 20 ms offset), then 510 s and 1,020 s later.
  const auto first = h.arrival_ms("55 55 05 06 00 01 00");
  const auto second = h.arrival_ms("55 55 05 06 01 01 00");
  const auto third = h.arrival_ms("55 55 05 06 02 01 00");
  ASSERT_TRUE(first && second && third) << r.err;
  EXPECT_NEAR(*first, 820.0, 1e-5);
  EXPECT_NEAR(*second, 510820.0, 1e-5);
  EXPECT_NEAR(*third, 1020820.0, 1e-5);
  EXPECT_NE(r.err.find("seqc: stored 3 chained groups starting on bars 1, 256 and 511 in groups "
                       "0-2 and started each at its bar line"),
            std::string::npos)
      << r.err;
}

// A board whose flash holds two groups refuses the third: the dance stops there, said with the
// group, and nothing is started.
TEST(DeviceMusic, ABoardWithTooFewGroupsRefusesTheChainBeforeAnyStart) {
  emu::XArmConfig config = at_9600();
  config.store.groups = 2;
  DeviceHarness h(config);
  h.files.add("long.yaml",
              "robot: xarm\ntempo: 120\nmeter: 4/4\nsequence:\n  - repeat: 1500\n    do:\n"
              "      - move: {base: 300}\n        time: 1b\n"
              "      - move: {base: 700}\n        time: 1b\n");
  const RunResult r = h.run({"upload", "long.yaml", "--port", "emu:xarm", "--run", "--force"});
  EXPECT_EQ(r.code, 4) << r.err;
  EXPECT_NE(r.err.find("seqc: error: piece 3 (group 2): the controller refused step 1 (open "
                       "group 2)"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(h.received().find("5555050602"), std::string::npos);  // no GroupRun at all
  EXPECT_EQ(h.received().find("5555050600"), std::string::npos);
}

// Features meeting: a chained dance that opens with a rest and whose first move is relative to
// where the robot stands. The base stands at 420: the rest is an action naming no servo (one
// bar: 2 beats of wait), the first move takes it to 470, then 700 passes of two one-beat moves:
// 1,402 actions. Group 0 holds bar 1 (2 actions) and bars 2-255 (254 x 4): 1,018 actions, so
// group 1 starts on bar 256, 255 x 2 s = 510 s in, with the 384 left.
TEST(DeviceMusic, AChainedDanceOpeningWithARestFromWhereTheRobotStands) {
  emu::XArmConfig config = at_9600();
  config.initial_positions = {{6, 420}};
  DeviceHarness h(config);
  h.files.add("rest.yaml",
              "robot: xarm\ntempo: 120\nmeter: 4/4\nsequence:\n  - wait: 2b\n"
              "  - move: {base: +50}\n    time: 2b\n  - repeat: 700\n    do:\n"
              "      - move: {base: 300}\n        time: 1b\n"
              "      - move: {base: 700}\n        time: 1b\n");
  const RunResult r = h.run({"upload", "rest.yaml", "--port", "emu:xarm", "--run", "--force"});
  ASSERT_EQ(r.code, 0) << r.err;
  const auto g0 = h.emu.stored_group(0);
  const auto g1 = h.emu.stored_group(1);
  ASSERT_TRUE(g0 && g1) << r.err;
  ASSERT_EQ(g0->size(), 1018u);
  ASSERT_EQ(g1->size(), 384u);
  EXPECT_EQ((*g0)[0].time_ms, 1000u);
  EXPECT_TRUE((*g0)[0].servos.empty());  // the rest names no servo
  ASSERT_EQ((*g0)[1].servos.size(), 1u);
  EXPECT_EQ((*g0)[1].servos[0].position, 470u);  // 420 + 50
  EXPECT_EQ((*g1)[0].servos[0].position, 300u);
  std::vector<io::TimePoint> runs;
  for (const emu::ReceivedFrame& f : h.emu.received()) {
    const std::string x = to_hex(f.raw);
    if (x == hex("55 55 05 06 00 01 00") || x == hex("55 55 05 06 01 01 00")) runs.push_back(f.at);
  }
  ASSERT_EQ(runs.size(), 2u) << r.err;
  EXPECT_EQ(runs[1] - runs[0], std::chrono::duration_cast<io::Duration>(milliseconds(510000)));
}

}  // namespace
}  // namespace seqc::cli::test
