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
constexpr const char* kWalkRefused =
    "seqc: error: emu:xarm cannot keep this schedule: move 12 of 29 at 4.12 s "
    "(examples/walk.yaml:27) would leave 6.0 ms late: at 9600 baud the move before it takes "
    "26.0 ms on the wire (1 of 29 moves late, the worst by 6.0 ms)\n"
    "  hint: store it on the controller and run it there: seqc upload examples/walk.yaml --run\n"
    "  hint: or play it late anyway with --allow-late\n";

TEST(PlayLive, RefusesASchedule9600BaudCannotKeep) {
  SeqcRun r = seqc(kSource, "play examples/walk.yaml --port emu:xarm");
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.err, kWalkRefused);
}

TEST(PlayLive, AllowLatePlaysAndMeasuresTheLateMove) {
  SeqcRun r = seqc(kSource, "play examples/walk.yaml --port emu:xarm --allow-late");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("seqc: warning: emu:xarm cannot keep this schedule: move 12 of 29"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("seqc: played 29 moves, 8 s; moves left the port late by p50 0.0 ms, "
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
  EXPECT_NE(r.err.find("seqc: played 42 moves, 7.5 s"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace seqc::testing
