// The `clock` fault: a board whose oscillator is fast or slow plays its stored actions in that
// much less or more host time. Every expected time is board time / (1 + ppm / 1e6), worked
// out below to the nanosecond.
#include <gtest/gtest.h>

#include "runtime/emulator/board_clock.hpp"
#include "tests/emulator/emu_test_util.hpp"
#include "tests/emulator/lsc6_test_util.hpp"

namespace seqc::emu::test {
namespace {

TEST(BoardClock, ParsesPercentsAndPpm) {
  EXPECT_EQ(parse_clock_error("+0.8%").value(), 8000);
  EXPECT_EQ(parse_clock_error("-1%").value(), -10000);
  EXPECT_EQ(parse_clock_error("+120ppm").value(), 120);
  EXPECT_EQ(parse_clock_error("-0.0015%").value(), -15);
  EXPECT_EQ(parse_clock_error("2.5%").value(), 25000);
  EXPECT_EQ(parse_clock_error("0").value(), 0);
  for (const char* bad :
       {"", "+", "1", "0.8", "+1.5ppm", "+0.00001%", "+%", "x%", "1.%", "+21%", "1e3ppm"}) {
    EXPECT_FALSE(parse_clock_error(bad)) << bad;
  }
  EXPECT_EQ(format_clock_error(8000), "+8000ppm");
  EXPECT_EQ(format_clock_error(-10000), "-10000ppm");
}

TEST(BoardClock, BoardTimeToHostTime) {
  using std::chrono::milliseconds;
  // 1000 ms / 1.008 = 992.063492063... ms; / 0.99 = 1010.101010... ms; / 1.00012 = 999.880014...
  EXPECT_EQ(board_to_host(milliseconds(1000), 8000), io::Duration{992063492});
  EXPECT_EQ(board_to_host(milliseconds(1000), -10000), io::Duration{1010101010});
  EXPECT_EQ(board_to_host(milliseconds(1000), 120), io::Duration{999880014});
  EXPECT_EQ(board_to_host(milliseconds(1000), 0), io::Duration{1000000000});
  // The longest a run can last (65535 loops of 1,020 actions of 30 s) does not overflow:
  // 2,005,371,000 s on a clock 1 % slow is 2,025,627,272.727272727... s.
  EXPECT_EQ(board_to_host(std::chrono::seconds(2005371000LL), -10000),
            io::Duration{2025627272727272727LL});
}

TEST(BoardClock, AFastXarmFinishesItsGroupEarly) {
  XArmConfig config;
  ASSERT_TRUE(apply_emulator_options("clock=+0.8%", config).ok());
  EXPECT_EQ(config.faults.clock_ppm, 8000);
  EXPECT_EQ(describe_faults(config.faults), "clock=+8000ppm");
  XArmEmulator emu(config);
  io::TimePoint t{0};
  // 100 + 200 + 300 ms of the controller's clock.
  ASSERT_TRUE(download(emu, 1,
                       {lsc::GroupAction{100, {{1, 700}}}, lsc::GroupAction{200, {{1, 300}}},
                        lsc::GroupAction{300, {{2, 900}}}},
                       t));
  const io::TimePoint t0 = at_ms(1000);
  emu.receive(hex("55 55 05 06 01 02 00"), t0);  // twice
  EXPECT_EQ(hex_of(emu.take_output(t0)), "55 55 05 06 01 02 00");
  // Each action on its own: 100 / 1.008 = 99.206349206 ms -> 99,206,349 ns; 200 ms ->
  // 198,412,698 ns; 300 ms -> 297,619,047 ns. Two loops: 2 x 595,238,094 = 1,190,476,188 ns
  // (1200 / 1.008 = 1,190,476,190.47 ns: under a nanosecond lost per action).
  const io::TimePoint end = t0 + io::Duration{1190476188};
  EXPECT_EQ(emu.next_output_at(), end);
  EXPECT_EQ(emu.take_output(end - io::Duration{1}), Bytes{});
  EXPECT_EQ(hex_of(emu.take_output(end)), "55 55 05 08 01 02 00");
}

TEST(BoardClock, ASlowXarmFinishesLate) {
  XArmConfig config;
  ASSERT_TRUE(apply_emulator_options("clock=-1%", config).ok());
  XArmEmulator emu(config);
  io::TimePoint t{0};
  ASSERT_TRUE(download(emu, 1, {lsc::GroupAction{1000, {{1, 700}}}}, t));
  const io::TimePoint t0 = at_ms(1000);
  emu.receive(hex("55 55 05 06 01 01 00"), t0);
  EXPECT_EQ(hex_of(emu.take_output(t0)), "55 55 05 06 01 01 00");
  // 1000 / 0.99 ms.
  EXPECT_EQ(emu.next_output_at(), t0 + io::Duration{1010101010});
}

TEST(BoardClock, AFastLsc6AnnouncesTheEndEarly) {
  Lsc6Config config = unpaced();
  ASSERT_TRUE(apply_lsc6_options("clock=+120ppm", config).ok());
  EXPECT_EQ(config.clock_ppm, 120);
  Lsc6Emulator emu(config);
  io::TimePoint t = at_ms(0);
  (void)exchange(emu, download_action(0, 2, 0, 400, 3, 900), t);
  (void)exchange(emu, download_action(0, 2, 1, 600, 3, 2100), t);
  const io::TimePoint start = t;
  emu.receive(hex("55 55 05 06 00 01 00"), start);
  EXPECT_EQ(hex_of(emu.take_output(start)), "55 55 02 06");
  // 400 / 1.00012 = 399.952005759 ms -> 399,952,005 ns; 600 / 1.00012 = 599.928008639 ms ->
  // 599,928,008 ns; together 999,880,013 ns.
  const io::TimePoint end = start + io::Duration{999880013};
  EXPECT_EQ(hex_of(emu.take_output(end - io::Duration{1})), "");
  EXPECT_EQ(hex_of(emu.take_output(end)), "55 55 02 07");
  EXPECT_EQ(emu.pulse(3, end), 2100);
}

TEST(BoardClock, Lsc6RefusesABadClock) {
  Lsc6Config config;
  auto bad = apply_lsc6_options("clock=fast", config);
  ASSERT_FALSE(bad);
  EXPECT_NE(bad.error().message.find("clock=fast"), std::string::npos) << bad.error().message;
}

}  // namespace
}  // namespace seqc::emu::test
