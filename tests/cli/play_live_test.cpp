// `seqc play` on the servo controller is honest about the link: a schedule the line cannot keep
// is refused before anything is sent (or played late with --allow-late), and the lateness of
// every move, measured once its bytes have left, is reported. All against the in-process
// emulators at 9600 baud, in emulated time.
#include <gtest/gtest.h>

#include <string>

#include "tests/cli/seqc_run.hpp"

namespace seqc::testing {
namespace {

// walk.yaml's move 12 starts 20 ms after move 11, whose 25 bytes take 26.04 ms at 9600 baud.
// too-fast.yaml's second move, all six servos in 20 ms: its frame, 55 55 LEN 03 COUNT TIME_L
// TIME_H and 3 bytes per servo, is 7 + 18 = 25 bytes, 25 x 10 bits / 9600 baud = 26.0 ms on
// the wire, so the third move (at 1.02 s, line 9) leaves 6.0 ms late.
constexpr const char* kTooFastRefused =
    "seqc: error: emu:xarm cannot keep this schedule: move 3 of 3 at 1.02 s "
    "(tests/cli/data/too-fast.yaml:9) would leave 6.0 ms late: at 9600 baud the move before it "
    "takes 26.0 ms on the wire (1 of 3 moves late, the worst by 6.0 ms)\n"
    "  hint: store it on the controller and run it there: seqc upload "
    "tests/cli/data/too-fast.yaml --run\n"
    "  hint: or play it late anyway with --allow-late\n";

TEST(PlayLive, RefusesASchedule9600BaudCannotKeep) {
  SeqcRun r = seqc(kSource, "play tests/cli/data/too-fast.yaml --port emu:xarm");
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.err, kTooFastRefused);
}

TEST(PlayLive, AllowLatePlaysAndMeasuresTheLateMove) {
  SeqcRun r = seqc(kSource, "play tests/cli/data/too-fast.yaml --port emu:xarm --allow-late");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("seqc: warning: emu:xarm cannot keep this schedule: move 3 of 3"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("seqc: played 3 moves, 2.02 s; moves left the port late by p50 0.0 ms, "
                       "p99 6.0 ms, max 6.0 ms (measured once each had left)"),
            std::string::npos)
      << r.err;
}

TEST(PlayLive, AScheduleThatFitsLeavesOnTime) {
  SeqcRun r = seqc(kSource, "play examples/wave.yaml --port emu:xarm");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("late by p50 0.0 ms, p99 0.0 ms, max 0.0 ms"), std::string::npos) << r.err;
  SeqcRun unpaced = seqc(kSource, "play examples/walk.yaml --port emu:xarm?baud=0");
  EXPECT_EQ(unpaced.status, 0) << unpaced.err;
}

TEST(PlayLive, PlaysOnAnLsc6InItsOwnDialect) {
  SeqcRun r = seqc(kSource, "play examples/learm.yaml --port emu:lsc6");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("seqc: note: the LSC-6 answers no move"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("seqc: played 36 moves, 7.5 s"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace seqc::testing
