#include "base/units.hpp"

#include <gtest/gtest.h>

namespace seqc::compiler {
namespace {

TEST(ParseTime, UnitsAndFractions) {
  auto ms = parse_time("500ms");
  ASSERT_TRUE(ms);
  EXPECT_EQ(ms->unit, TimeUnit::Milliseconds);
  EXPECT_DOUBLE_EQ(ms->amount, 500);
  auto s = parse_time("1.5s");
  ASSERT_TRUE(s);
  EXPECT_EQ(s->unit, TimeUnit::Seconds);
  EXPECT_DOUBLE_EQ(s->amount, 1.5);
  auto b = parse_time("2b");
  ASSERT_TRUE(b);
  EXPECT_EQ(b->unit, TimeUnit::Beats);
}

TEST(ParseTime, FractionsAreExact) {
  auto third = parse_time("1/3b");
  ASSERT_TRUE(third);
  EXPECT_EQ(third->unit, TimeUnit::Beats);
  EXPECT_EQ(third->numerator, 1);
  EXPECT_EQ(third->denominator, 3);
  EXPECT_DOUBLE_EQ(third->amount, 1.0 / 3);
  auto bar = parse_time("1/6bar");
  ASSERT_TRUE(bar);
  EXPECT_EQ(bar->unit, TimeUnit::Bars);
  EXPECT_EQ(bar->denominator, 6);
  auto five = parse_time("5/4b");
  ASSERT_TRUE(five);
  EXPECT_EQ(five->numerator, 5);
  EXPECT_EQ(five->denominator, 4);
  auto s = parse_time("1/3s");
  ASSERT_TRUE(s);
  EXPECT_EQ(s->unit, TimeUnit::Seconds);
  EXPECT_EQ(parse_time("1000000/1000ms")->numerator, 1000000);
  EXPECT_EQ(parse_time("1.5s")->denominator, 0);  // a decimal is what it says
  EXPECT_NEAR(*parse_clock_ms("1/3s"), 1000.0 / 3, 1e-9);
}

TEST(ParseTime, FractionMistakes) {
  EXPECT_EQ(parse_time("1/0b").error().message,
            "'1/0b': the denominator of a fraction must be a whole number from 1 to 1,000, e.g. "
            "'1/3b'");
  EXPECT_EQ(parse_time("1000001/2b").error().message,
            "'1000001/2b': the numerator of a fraction must be a whole number up to 1,000,000; "
            "write longer times in a larger unit");
  EXPECT_EQ(parse_time("2/3").error().message,
            "time '2/3' has no unit; write '2/3b' (beats), '2/3bar', '2/3s' or '2/3ms'");
  EXPECT_EQ(parse_time("(2/3)bar").error().message,
            "'(2/3)bar' is not a time; a fraction is written whole over whole with the unit "
            "after it, e.g. '2/3bar'");
  EXPECT_EQ(parse_time("1s/3").error().message,
            "'1s/3' is not a time; a fraction is written whole over whole with the unit after "
            "it, e.g. '1/3s'");
  for (const char* bad : {"/3b", "1/b", "1//3b", "-1/3b", "1/-3b", "1/3 b", "1/3/4b"}) {
    EXPECT_FALSE(parse_time(bad)) << bad;
  }
}

TEST(ParseTime, BareNumberSuggestsUnits) {
  auto t = parse_time("500");
  ASSERT_FALSE(t);
  EXPECT_EQ(t.error().message, "time '500' has no unit; write '500ms' or '500s'");
}

TEST(ParseTime, Rejects) {
  for (const char* bad : {"", "ms", "-5ms", "1.s", "5 ms", "1e3ms", "2sec", ".5s"}) {
    EXPECT_FALSE(parse_time(bad)) << bad;
  }
}

TEST(ParsePosition, Forms) {
  auto abs = parse_position("500");
  ASSERT_TRUE(abs);
  EXPECT_FALSE(abs->relative);
  EXPECT_FALSE(abs->degrees);
  EXPECT_DOUBLE_EQ(abs->amount, 500);
  auto deg = parse_position("90deg");
  ASSERT_TRUE(deg);
  EXPECT_TRUE(deg->degrees);
  auto up = parse_position("+50");
  ASSERT_TRUE(up);
  EXPECT_TRUE(up->relative);
  EXPECT_DOUBLE_EQ(up->amount, 50);
  auto down = parse_position("-2.5deg");
  ASSERT_TRUE(down);
  EXPECT_TRUE(down->relative && down->degrees);
  EXPECT_DOUBLE_EQ(down->amount, -2.5);
}

TEST(ParsePosition, Rejects) {
  for (const char* bad : {"", "+", "deg", "50.5", "5O0", "++5", "90 deg", "90degs"}) {
    EXPECT_FALSE(parse_position(bad)) << bad;
  }
}

TEST(ParsePosition, AWholeNumberMayBeWrittenWithZeroDecimals) {
  EXPECT_DOUBLE_EQ(parse_position("1000.0")->amount, 1000);
  EXPECT_DOUBLE_EQ(parse_position("-20.00")->amount, -20);
  EXPECT_EQ(parse_position("500.5").error().message,
            "position '500.5' is not a whole number of device units; round it to 500 or 501 (an "
            "angle may have a fraction: 90.5deg)");
  EXPECT_EQ(parse_position("-2.5").error().message,
            "position '-2.5' is not a whole number of device units; round it to -2 or -3 (an "
            "angle may have a fraction: 90.5deg)");
}

TEST(ParseSpeed, UnitsAndDegrees) {
  auto u = parse_speed("400/s");
  ASSERT_TRUE(u);
  EXPECT_FALSE(u->degrees);
  EXPECT_DOUBLE_EQ(u->per_second, 400);
  auto d = parse_speed("90deg/s");
  ASSERT_TRUE(d);
  EXPECT_TRUE(d->degrees);
  EXPECT_FALSE(parse_speed("400"));
  EXPECT_FALSE(parse_speed("0/s"));
}

TEST(FormatSeconds, TrimsZeros) {
  EXPECT_EQ(format_seconds(0), "0 s");
  EXPECT_EQ(format_seconds(12500), "12.5 s");
  EXPECT_EQ(format_seconds(5627), "5.627 s");
  EXPECT_EQ(format_seconds(8000), "8 s");
  EXPECT_EQ(format_seconds(1050), "1.05 s");
}

TEST(ParseClockMs, MillisecondsAndSecondsOnly) {
  EXPECT_EQ(parse_clock_ms("500ms"), 500.0);
  EXPECT_EQ(parse_clock_ms("1.5s"), 1500.0);
  EXPECT_EQ(parse_clock_ms("2b"), std::nullopt);  // beats need a tempo
  EXPECT_EQ(parse_clock_ms("1bar"), std::nullopt);
  EXPECT_EQ(parse_clock_ms("20"), std::nullopt);  // no unit
  EXPECT_EQ(parse_clock_ms("soon"), std::nullopt);
}

TEST(FormatGrouped, SeparatesThousands) {
  EXPECT_EQ(format_grouped(0), "0");
  EXPECT_EQ(format_grouped(999), "999");
  EXPECT_EQ(format_grouped(7985), "7,985");
  EXPECT_EQ(format_grouped(-10000), "-10,000");
  EXPECT_EQ(format_grouped(1234567), "1,234,567");
}

}  // namespace
}  // namespace seqc::compiler
