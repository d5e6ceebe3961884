// The timecode half of `seqc follow` in words (runtime/cli/follow_ltc): --start read or refused
// with the option named, SOURCE a WAV file when one exists, a missing .wav refused instead of
// asked of the sound server, and the clock it makes following the file on the context's clock.
#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "runtime/cli/follow_ltc.hpp"
#include "tests/follow/ltc_test_signals.hpp"

namespace seqc::cli {
namespace {

class NoFiles final : public FileReader {
 public:
  Result<std::string> read(const std::string& path) override {
    return make_error(path + ": not read in this test");
  }
};

struct CommandRun {
  std::ostringstream out, err;
  io::ManualClock clock;
  NoFiles files;
  Context ctx{out, err, clock, files};
};

TEST(FollowLtcCli, ReadsTheStartOrNamesTheOption) {
  EXPECT_EQ(*parse_ltc_start("01:00:00:00"), (ltc::Timecode{1, 0, 0, 0, false}));
  EXPECT_EQ(*parse_ltc_start("00:10:00;00"), (ltc::Timecode{0, 10, 0, 0, true}));
  EXPECT_EQ(parse_ltc_start("1:00").error().message,
            "--start: expected a timecode HH:MM:SS:FF (HH:MM:SS;FF for drop-frame), got \"1:00\"");
  EXPECT_EQ(parse_ltc_start("00:02:00;00").error().message,
            "--start: 00:02:00;00 does not exist in drop-frame timecode (frames 0 and 1 are "
            "skipped at every minute but each tenth)");
}

TEST(FollowLtcCli, AMissingWavFileIsNotASoundServerSource) {
  CommandRun run;
  auto clock = open_ltc_clock("/nonexistent/show.wav", {1, 0, 0, 0, false}, run.ctx);
  ASSERT_FALSE(clock.ok());
  EXPECT_EQ(clock.error().message, "--ltc: /nonexistent/show.wav: no such file");
}

TEST(FollowLtcCli, FollowsAWavFileOnTheContextsClock) {
  CommandRun run;
  auto clock =
      open_ltc_clock(testing::ltc_signal_path("ltc-show-25-48000"), {1, 0, 0, 0, false}, run.ctx);
  ASSERT_TRUE(clock.ok()) << clock.error().message;
  const io::TimePoint never{std::chrono::hours(1)};
  auto open = (*clock)->next(never);
  ASSERT_TRUE(open.has_value());
  EXPECT_EQ(open->kind, follow::ShowClockKind::Open);
  EXPECT_EQ(open->detail, "locked at 25 fps on 00:59:59:03");
  auto start = (*clock)->next(never);
  ASSERT_TRUE(start.has_value());
  EXPECT_EQ(start->kind, follow::ShowClockKind::Start);
  // Real-time pace on the manual clock: --start is a second into the file (to a sample).
  EXPECT_NEAR(static_cast<double>(start->at.count()), 1e9, 21e3);
  EXPECT_EQ(start->dance_ms, 0.0);
  // A deadline already passed gives nothing and reads nothing.
  const io::TimePoint now = run.clock.now();
  EXPECT_FALSE((*clock)->next(now).has_value());
  EXPECT_EQ(run.clock.now(), now);
}

}  // namespace
}  // namespace seqc::cli
