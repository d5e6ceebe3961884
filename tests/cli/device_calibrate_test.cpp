// `seqc calibrate clock` against emulated controllers whose clock is fast or slow (the emulator's
// `clock` fault), and `--clock-ppm` / `--rig` on the commands that compile. The expected ppm is
// worked out in each test from the fault and the emulator's nanosecond arithmetic.
#include <gtest/gtest.h>

#include "tests/cli/device_test_util.hpp"
#include "tests/six_bars_dance.hpp"

namespace seqc::cli::test {
namespace {

emu::XArmConfig with_clock(const std::string& spec, std::uint32_t baud = 0) {
  emu::XArmConfig config;
  EXPECT_TRUE(emu::apply_emulator_options(spec + ",1=300,2=650", config).ok());
  config.baud = baud;
  return config;
}

TEST(CalibrateClock, AFastClockMeasuresPlus8000Ppm) {
  DeviceHarness h(with_clock("clock=+0.8%"));
  RunResult r = h.run({"calibrate", "clock", "--port", "emu:xarm", "--runs", "5"});
  ASSERT_EQ(r.code, 0) << r.err;
  // 20 s in 4 actions of 5000 ms; each lasts 5000 / 1.008 ms = 4,960,317,460 ns (truncated), so
  // a run lasts 19,841,269,840 ns and shows 20 / 19.84126984 - 1 = +0.0080000000 (8000 ppm,
  // 6e-5 ppm off): +8000 within the spread, which is 0 in emulated time.
  EXPECT_EQ(r.out,
            "clock: +8,000 ppm \u00b1 0 (5 runs of 20.000 s)\n"
            "rig file (--rig): clock_ppm: +8000\n");
  // The measuring group: group 254, four actions of 5000 ms holding every servo where it was
  // read (1 at 300, 2 at 650, the others at home, 500).
  const auto stored = h.emu.stored_group(254);
  ASSERT_TRUE(stored.has_value());
  ASSERT_EQ(stored->size(), 4u);
  for (const lsc::GroupAction& a : *stored) {
    EXPECT_EQ(a.time_ms, 5000);
    EXPECT_EQ(a.servos, (std::vector<lsc::ServoTarget>{
                            {1, 300}, {2, 650}, {3, 500}, {4, 500}, {5, 500}, {6, 500}}));
  }
  // Five runs of group 254 once: 55 55 05 06 fe 01 00.
  std::size_t runs = 0;
  const std::string run = hex("55 55 05 06 fe 01 00");
  for (std::size_t at = h.received().find(run); at != std::string::npos;
       at = h.received().find(run, at + 1)) {
    ++runs;
  }
  EXPECT_EQ(runs, 5u);
}

TEST(CalibrateClock, ASlowClockOnAPacedLineMeasuresMinus10000Ppm) {
  // At 9600 baud each notice takes 7 x 10 bits = 7.29 ms to arrive: the same for the start and
  // the finish, so it cancels. 4 x 1000 ms / 0.99 = 4 x 1,010,101,010 ns = 4,040,404,040 ns:
  // 4 / 4.04040404 - 1 = -0.0099999999 (-10,000 ppm).
  DeviceHarness h(with_clock("clock=-1%", 9600));
  RunResult r = h.run({"calibrate", "clock", "--port", "emu:xarm", "--runs", "2", "--length", "4s",
                       "--group", "7"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.out,
            "clock: -10,000 ppm \u00b1 0 (2 runs of 4.000 s)\n"
            "rig file (--rig): clock_ppm: -10000\n");
  EXPECT_TRUE(h.emu.stored_group(7).has_value());
}

TEST(CalibrateClock, ARunLongerThanOneActionIsSeveralActionsAndMeasuresTheSame) {
  // An action lasts at most 30 s, so a 130 s run is ceil(130 / 30) = 5 actions of 26,000 ms.
  // On a clock 2 % slow each lasts 26000 / 0.98 ms = 26,530,612,244 ns (truncated), a run
  // 5 x that = 132,653,061,220 ns: 130 / 132.65306122 - 1 = -0.01999999997 (-20,000 ppm, 3e-5
  // ppm off), the same in both runs, so a spread of 0.
  DeviceHarness h(with_clock("clock=-2%"));
  RunResult r = h.run({"calibrate", "clock", "--port", "emu:xarm", "--runs", "2", "--length",
                       "130s", "--group", "9"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.out,
            "clock: -20,000 ppm \u00b1 0 (2 runs of 130.000 s)\n"
            "rig file (--rig): clock_ppm: -20000\n");
  const auto stored = h.emu.stored_group(9);
  ASSERT_TRUE(stored.has_value());
  ASSERT_EQ(stored->size(), 5u);
  for (const lsc::GroupAction& a : *stored) EXPECT_EQ(a.time_ms, 26000);
}

TEST(CalibrateClock, AnExactClockMeasuresZero) {
  DeviceHarness h;
  RunResult r =
      h.run({"calibrate", "clock", "--port", "emu:xarm", "--runs", "1", "--length", "1s"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.out, "clock: 0 ppm \u00b1 0 (1 run of 1.000 s)\nrig file (--rig): clock_ppm: 0\n");
}

TEST(CalibrateClock, ABadLengthIsAUsageError) {
  DeviceHarness h;
  RunResult r = h.run({"calibrate", "clock", "--port", "emu:xarm", "--length", "2b"});
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err, "seqc: error: --length: give ms or s, e.g. 20s\n");
  EXPECT_EQ(h.received(), "");
}

TEST(CalibrateClock, AControllerThatNeverFinishesIsADeviceFailure) {
  // The reading (1 frame), the upload (12) and then silence: the 14th frame, GroupRun, is never
  // answered, so no run is timed and nothing is printed on stdout.
  DeviceHarness h(with_clock("silent-after=13"));
  RunResult r =
      h.run({"calibrate", "clock", "--port", "emu:xarm", "--runs", "1", "--length", "1s"});
  EXPECT_EQ(r.code, 4) << r.err;
  EXPECT_EQ(r.out, "");
  EXPECT_NE(r.err.find("no reply from the controller on emu:xarm within 1 s (waiting for the "
                       "group-started notice)"),
            std::string::npos)
      << r.err;
  const std::string run = hex("55 55 05 06 fe 01 00");
  EXPECT_EQ(h.received().substr(h.received().size() - run.size()), run);
}

TEST(CalibrateClock, AnLsc6IsTimedFromItsRunAnswerToItsEndNotice) {
  // The LSC-6 cannot say where its servos are: the four actions name none. 4 x 1000 ms on a
  // clock 1 % slow: 4 x 1,010,101,010 ns, -10,000 ppm as on the xArm.
  DeviceHarness h;
  RunResult r = h.run({"calibrate", "clock", "--port", "emu:lsc6?clock=-1%", "--runs", "2",
                       "--length", "4s", "--group", "3"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.out,
            "clock: -10,000 ppm \u00b1 0 (2 runs of 4.000 s)\n"
            "rig file (--rig): clock_ppm: -10000\n");
  EXPECT_NE(r.err.find("seqc: note: the board cannot say where its servos are, so the measuring "
                       "actions named none\n"),
            std::string::npos)
      << r.err;
}

// ---- --clock-ppm and --rig ---------------------------------------------------------------------

const char* kTwoSeconds = R"(robot: xarm
sequence:
  - move: {base: 600}
    time: 1s
  - move: {base: 400}
    time: 1s
)";

TEST(ClockPpmOption, CompilePreScalesTheActionTimes) {
  DeviceHarness h;
  h.files.add("dance.yaml", kTwoSeconds);
  // 1000 ms x 1.008 = 1008 ms = 0x03f0: each action's time field reads f0 03.
  RunResult r = h.run({"compile", "dance.yaml", "--clock-ppm", "+8000", "--emit", "json"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("\"start_ms\": 1008"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("\"start_ms\": 1000"), std::string::npos) << r.out;
  h.files.add("rig.yaml", "clock_ppm: -10000\naudio_offset: 40ms\n");
  r = h.run({"compile", "dance.yaml", "--rig", "rig.yaml", "--emit", "json"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("\"start_ms\": 990"), std::string::npos) << r.out;  // 1000 x 0.99
  // --clock-ppm wins over the rig file.
  r = h.run({"compile", "dance.yaml", "--rig", "rig.yaml", "--clock-ppm", "0", "--emit", "json"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("\"start_ms\": 1000"), std::string::npos) << r.out;
}

TEST(ClockPpmOption, UploadStoresThePreScaledTimes) {
  DeviceHarness h;
  h.files.add("dance.yaml", kTwoSeconds);
  RunResult r = h.run({"upload", "dance.yaml", "--port", "emu:xarm", "--clock-ppm", "8000"});
  ASSERT_EQ(r.code, 0) << r.err;
  const auto stored = h.emu.stored_group(0);
  ASSERT_TRUE(stored.has_value());
  ASSERT_EQ(stored->size(), 2u);
  EXPECT_EQ((*stored)[0].time_ms, 1008);
  EXPECT_EQ((*stored)[1].time_ms, 1008);
}

TEST(ClockPpmOption, ABadValueIsAUsageError) {
  DeviceHarness h;
  h.files.add("dance.yaml", kTwoSeconds);
  RunResult r = h.run({"compile", "dance.yaml", "--clock-ppm", "0.8%"});
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err,
            "seqc: error: --clock-ppm: a clock error is a whole number of ppm, e.g. +8000 or "
            "-120, not '0.8%'\n");
  r = h.run({"compile", "dance.yaml", "--clock-ppm", "+250000"});
  EXPECT_EQ(r.code, 2);
}

TEST(RigFile, EveryMistakeIsReportedWithItsPlace) {
  DeviceHarness h;
  h.files.add("dance.yaml", kTwoSeconds);
  h.files.add("rig.yaml", "clock_pmm: +8000\naudio_offset: soon\nclock_ppm: 1.5\n");
  RunResult r = h.run({"check", "dance.yaml", "--rig", "rig.yaml"});
  EXPECT_EQ(r.code, 1);
  EXPECT_EQ(r.out, "");
  EXPECT_NE(r.err.find("rig.yaml:1:1: error: unknown rig key 'clock_pmm'; did you mean "
                       "'clock_ppm'? (known: clock_ppm, audio_offset)"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("rig.yaml:2:15: error: audio_offset is a time in ms or s"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("rig.yaml:3:12: error: a clock error is a whole number of ppm"),
            std::string::npos)
      << r.err;
  r = h.run({"check", "dance.yaml", "--rig", "missing.yaml"});
  EXPECT_EQ(r.code, 5);
}

}  // namespace
}  // namespace seqc::cli::test

namespace seqc::cli::test {
namespace {

// ---- upload --resync ---------------------------------------------------------------------------

// Six bars at 120 bpm in 4/4 (12 s), the base swinging each beat: 8 actions every 2 bars.
constexpr const char* kSixBars = seqc::testing::kSixBarsDance;

TEST(Resync, EachPieceIsStartedByTheComputerAtItsBarLine) {
  // A board 1 % slow: a 4 s piece lasts 4.0404 s there, so the computer's start of the next one
  // (a GroupStop and a GroupRun in one write) comes while it is still playing and cuts it short.
  DeviceHarness h(with_clock("clock=-1%"));
  h.files.add("dance.yaml", kSixBars);
  RunResult r = h.run(
      {"upload", "dance.yaml", "--port", "emu:xarm", "--run", "--resync", "2", "--group", "5"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("seqc: stored 3 pieces of 2 bars in groups 5-7 and started each at its "
                       "bar line (the latest 0.0 ms late)\n"),
            std::string::npos)
      << r.err;
  for (const int g : {5, 6, 7}) {
    const auto stored = h.emu.stored_group(static_cast<std::uint8_t>(g));
    ASSERT_TRUE(stored.has_value()) << g;
    EXPECT_EQ(stored->size(), 8u);
  }
  // GroupStop (55 55 02 07), then GroupRun of each group once (55 55 05 06 G 01 00), 4 s apart.
  std::vector<io::TimePoint> runs;
  for (const emu::ReceivedFrame& f : h.emu.received()) {
    if (f.frame && f.frame->cmd == 0x06) runs.push_back(f.at);
  }
  ASSERT_EQ(runs.size(), 3u);
  EXPECT_EQ(runs[1] - runs[0], std::chrono::seconds(4));
  EXPECT_EQ(runs[2] - runs[0], std::chrono::seconds(8));
  EXPECT_NE(h.received().find(hex("55 55 02 07 55 55 05 06 06 01 00")), std::string::npos);
  EXPECT_EQ(h.emu.playing_group(), std::optional<std::uint8_t>(7));
}

TEST(Resync, NeedsRun) {
  DeviceHarness h;
  h.files.add("dance.yaml", kTwoSeconds);
  RunResult r = h.run({"upload", "dance.yaml", "--port", "emu:xarm", "--resync", "2"});
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(h.received(), "");
}

TEST(CalibrateClock, AnLsc6CopyWithoutAnEndNoticeCannotBeMeasured) {
  DeviceHarness h;
  RunResult r = h.run(
      {"calibrate", "clock", "--port", "emu:lsc6?no-finish", "--runs", "1", "--length", "1s"});
  EXPECT_EQ(r.code, 4) << r.err;
  EXPECT_EQ(r.out, "");
  EXPECT_NE(r.err.find("the end-of-run notice"), std::string::npos) << r.err;
}

TEST(Resync, PiecesBeyondGroup254AreRefusedBeforeAnythingIsStored) {
  DeviceHarness h;
  h.files.add("dance.yaml", kSixBars);
  RunResult r = h.run(
      {"upload", "dance.yaml", "--port", "emu:xarm", "--run", "--resync", "1", "--group", "252"});
  EXPECT_EQ(r.code, 1);
  EXPECT_EQ(r.err,
            "seqc: error: dance.yaml: 6 pieces of 1 bar need groups 252-257; groups go up to 254 "
            "(give a lower --group or more bars)\n");
  EXPECT_FALSE(h.emu.stored_group(252).has_value());
  EXPECT_EQ(h.received(), "") << "nothing was sent";
}

}  // namespace
}  // namespace seqc::cli::test
