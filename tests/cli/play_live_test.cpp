// `seqc play` on the servo controller is honest about the link: a schedule the line cannot keep
// is refused before anything is sent (or played late with --allow-late), and the lateness of
// every move, measured once its bytes have left, is reported. All against the in-process
// emulators at 9600 baud, in emulated time.
#include <gtest/gtest.h>

#include <string>

#include "tests/cli/seqc_run.hpp"

namespace seqc::testing {
namespace {

// too-dense.yaml's moves 2 and 3 change all six servos: 3 + 3 x 6 + 2 = 23 data bytes, a 25-byte
// frame, 25 x 1.0417 ms = 26.04 ms at 9600 baud. Each is written to finish arriving at its time:
// move 2 holds the line until 1000 ms, move 3 should start leaving at 1020 - 26.04 = 993.96 ms,
// so 6.0 ms late.
constexpr const char* kDenseRefused =
    "seqc: error: emu:xarm cannot keep this schedule: move 3 of 3 at 1.02 s "
    "(tests/cli/data/too-dense.yaml:12) would leave 6.0 ms late: at 9600 baud the move before it "
    "takes 26.0 ms on the wire (1 of 3 moves late, the worst by 6.0 ms)\n"
    "  hint: store it on the controller and run it there: seqc upload "
    "tests/cli/data/too-dense.yaml --run\n"
    "  hint: or play it late anyway with --allow-late\n";

TEST(PlayLive, RefusesASchedule9600BaudCannotKeep) {
  SeqcRun r = seqc(kSource, "play tests/cli/data/too-dense.yaml --port emu:xarm");
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.err, kDenseRefused);
}

TEST(PlayLive, AllowLatePlaysAndMeasuresTheLateMove) {
  SeqcRun r = seqc(kSource, "play tests/cli/data/too-dense.yaml --port emu:xarm --allow-late");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("seqc: warning: emu:xarm cannot keep this schedule: move 3 of 3"),
            std::string::npos)
      << r.err;
  // Lateness 0, 0 and 6.0 ms: the median 0.0, p99 and the largest 6.0.
  EXPECT_NE(r.err.find("seqc: played 3 moves, 2.02 s; moves left the port late by p50 0.0 ms, "
                       "p99 6.0 ms, max 6.0 ms (measured once each had left)"),
            std::string::npos)
      << r.err;
}

// Each move carries only the servos whose target changes, so the examples keep 9600 baud's
// schedule without --allow-late (walk.yaml's move 12 was 6 ms late while every move carried all
// six servos).
TEST(PlayLive, TheExamplesLeaveOnTimeAt9600Baud) {
  for (const char* name : {"walk", "wave", "dance", "waltz"}) {
    SCOPED_TRACE(name);
    SeqcRun r = seqc(kSource, std::string("play examples/") + name + ".yaml --port emu:xarm");
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.err.find("cannot keep this schedule"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("late by p50 0.0 ms, p99 0.0 ms, max 0.0 ms"), std::string::npos) << r.err;
  }
  SeqcRun unpaced = seqc(kSource, "play tests/data/walk-joints.yaml --port emu:xarm?baud=0");
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
