// Timecode arithmetic by hand: frame counts at each rate, the drop-frame rule at the minute and
// the tenth minute, and the `--start` text with its errors.
#include <gtest/gtest.h>

#include "protocol/ltc_timecode.hpp"

namespace seqc::ltc {
namespace {

Timecode tc(int h, int m, int s, int f, bool drop = false) { return {h, m, s, f, drop}; }

TEST(LtcTimecode, CountsAtTheWholeRates) {
  EXPECT_EQ(frame_count(tc(0, 0, 1, 0), FrameRate::Fps24), 24);
  EXPECT_EQ(frame_count(tc(0, 0, 1, 0), FrameRate::Fps25), 25);
  EXPECT_EQ(frame_count(tc(0, 0, 1, 0), FrameRate::Fps30), 30);
  EXPECT_EQ(frame_count(tc(10, 0, 0, 0), FrameRate::Fps25), 900000);
  EXPECT_EQ(frame_count(tc(1, 2, 3, 4), FrameRate::Fps24), 89356);  // (3723 x 24) + 4
  EXPECT_EQ(to_timecode(89356, FrameRate::Fps24), tc(1, 2, 3, 4));
  EXPECT_EQ(to_timecode(900000 + 24, FrameRate::Fps25), tc(10, 0, 0, 24));
}

TEST(LtcTimecode, DropFrameSkipsTwoLabelsAtEachMinuteButTheTenth) {
  const FrameRate df = FrameRate::Fps2997Drop;
  EXPECT_EQ(frame_count(tc(0, 0, 59, 29, true), df), 1799);
  EXPECT_EQ(frame_count(tc(0, 1, 0, 2, true), df), 1800);
  EXPECT_EQ(frame_count(tc(0, 2, 0, 2, true), df), 3598);
  EXPECT_EQ(frame_count(tc(0, 9, 59, 29, true), df), 17981);
  EXPECT_EQ(frame_count(tc(0, 10, 0, 0, true), df), 17982);
  EXPECT_EQ(frame_count(tc(0, 11, 0, 2, true), df), 19782);
  EXPECT_EQ(frame_count(tc(1, 0, 0, 0, true), df), 107892);

  EXPECT_EQ(to_timecode(1799, df), tc(0, 0, 59, 29, true));
  EXPECT_EQ(to_timecode(1800, df), tc(0, 1, 0, 2, true));
  EXPECT_EQ(to_timecode(3597, df), tc(0, 1, 59, 29, true));
  EXPECT_EQ(to_timecode(3598, df), tc(0, 2, 0, 2, true));
  EXPECT_EQ(to_timecode(17981, df), tc(0, 9, 59, 29, true));
  EXPECT_EQ(to_timecode(17982, df), tc(0, 10, 0, 0, true));
  EXPECT_EQ(to_timecode(17983, df), tc(0, 10, 0, 1, true));
  EXPECT_EQ(to_timecode(19782, df), tc(0, 11, 0, 2, true));

  EXPECT_FALSE(exists_at(tc(0, 1, 0, 0, true), df));
  EXPECT_FALSE(exists_at(tc(0, 1, 0, 1, true), df));
  EXPECT_TRUE(exists_at(tc(0, 1, 0, 2, true), df));
  EXPECT_TRUE(exists_at(tc(0, 10, 0, 0, true), df));
  EXPECT_TRUE(exists_at(tc(0, 1, 1, 0, true), df));
  EXPECT_FALSE(exists_at(tc(0, 0, 0, 25), FrameRate::Fps25));
  EXPECT_FALSE(exists_at(tc(0, 0, 0, 24), FrameRate::Fps24));
  EXPECT_TRUE(exists_at(tc(0, 0, 0, 29), FrameRate::Fps30));
}

TEST(LtcTimecode, MillisecondsAtTheRealRate) {
  EXPECT_DOUBLE_EQ(frame_start_ms(25, FrameRate::Fps25), 1000.0);
  EXPECT_DOUBLE_EQ(frame_start_ms(3, FrameRate::Fps24), 125.0);
  EXPECT_DOUBLE_EQ(frame_start_ms(30, FrameRate::Fps30), 1000.0);
  EXPECT_NEAR(frame_start_ms(30, FrameRate::Fps2997Drop), 1001.0, 1e-9);
  // Ten minutes of drop-frame are 17982 real frames: 0.6 ms short of ten minutes.
  EXPECT_NEAR(frame_start_ms(17982, FrameRate::Fps2997Drop), 599999.4, 1e-6);
}

TEST(LtcTimecode, ReadsTheStartOption) {
  EXPECT_EQ(*parse_timecode("01:00:00:00"), tc(1, 0, 0, 0));
  EXPECT_EQ(*parse_timecode("1:2:3:4"), tc(1, 2, 3, 4));
  EXPECT_EQ(*parse_timecode("00:10:00;00"), tc(0, 10, 0, 0, true));
  EXPECT_EQ(*parse_timecode("00:01:00.02"), tc(0, 1, 0, 2, true));
  EXPECT_EQ(*parse_timecode("00;01;00;02"), tc(0, 1, 0, 2, true));
  EXPECT_EQ(to_text(tc(0, 1, 0, 2, true)), "00:01:00;02");
  EXPECT_EQ(to_text(tc(10, 0, 5, 24)), "10:00:05:24");
}

TEST(LtcTimecode, SaysWhatIsWrongWithAStart) {
  EXPECT_EQ(parse_timecode("12:00").error().message,
            "expected a timecode HH:MM:SS:FF (HH:MM:SS;FF for drop-frame), got \"12:00\"");
  EXPECT_EQ(parse_timecode("01:00:00:00x").error().message,
            "expected a timecode HH:MM:SS:FF (HH:MM:SS;FF for drop-frame), got \"01:00:00:00x\"");
  EXPECT_EQ(parse_timecode("001:00:00:00").error().message,
            "expected a timecode HH:MM:SS:FF (HH:MM:SS;FF for drop-frame), got \"001:00:00:00\"");
  EXPECT_EQ(parse_timecode("00;01:00;02").error().message,
            "expected a timecode HH:MM:SS:FF (HH:MM:SS;FF for drop-frame), got \"00;01:00;02\"");
  EXPECT_EQ(parse_timecode("24:00:00:00").error().message, "hours 24 is past 23 in 24:00:00:00");
  EXPECT_EQ(parse_timecode("00:60:00:00").error().message, "minutes 60 is past 59 in 00:60:00:00");
  EXPECT_EQ(parse_timecode("00:00:60:00").error().message, "seconds 60 is past 59 in 00:00:60:00");
  EXPECT_EQ(parse_timecode("00:00:00:30").error().message,
            "frame 30 is past 29 (30 fps) in 00:00:00:30");
  EXPECT_EQ(parse_timecode("00:01:00;01").error().message,
            "00:01:00;01 does not exist in drop-frame timecode (frames 0 and 1 are skipped at "
            "every minute but each tenth)");
}

}  // namespace
}  // namespace seqc::ltc
