// Device readings as text tables (runtime/boards/reading_table.hpp): columns padded to the widest
// cell, no trailing spaces, a row for every servo asked for and the missing ones listed.
#include <gtest/gtest.h>

#include "runtime/boards/reading_table.hpp"
#include "runtime/boards/servo_args.hpp"

namespace seqc::boards {
namespace {

TEST(ReadingTable, ColumnsArePaddedAndLinesNotTrailed) {
  Table t({"servo", "position"});
  t.add({"1", "500"});
  t.add({"12", ""});
  EXPECT_EQ(t.render(), "servo  position\n1      500\n12\n");
}

TEST(ReadingTable, EveryServoAskedForHasARow) {
  const std::vector<lsc::ServoTarget> answered{{6, 880}, {1, 120}};
  const ServoReadings r =
      servo_readings({1, 3, 6}, std::nullopt, "position", answered, &lsc::ServoTarget::position);
  EXPECT_EQ(r.column, "position");
  EXPECT_EQ(r.table, "servo  position\n1      120\n3      no answer\n6      880\n");
  EXPECT_EQ(r.missing, (std::vector<std::uint8_t>{3}));
}

TEST(ReadingTable, AProfileAddsTheServoNames) {
  const std::vector<lsc::ServoTarget> answered{{1, 200}};
  const ServoReadings r = servo_readings({1}, *robot_for_profile("xarm"), "position", answered,
                                         &lsc::ServoTarget::position);
  EXPECT_EQ(r.table, "servo  name  position\n1      claw  200\n");
  EXPECT_TRUE(r.missing.empty());
}

TEST(ReadingTable, BusServoLimitsAndState) {
  lsc::BusServoLimits l;
  l.position_min = 10;
  l.position_max = 990;
  l.millivolts_min = 4500;
  l.millivolts_max = 12000;
  l.temp_max = 85;
  l.led_status = 1;
  l.led_warning = 5;
  EXPECT_EQ(bus_servo_limits_table(3, l),
            "field           value\n"
            "id              3\n"
            "position-min    10\n"
            "position-max    990\n"
            "millivolts-min  4500\n"
            "millivolts-max  12000\n"
            "temp-max        85\n"
            "led             off\n"
            "led-warning     overheat,overposition\n");
  lsc::BusServoInfo info;
  info.offset = -4;
  info.position = 512;
  info.temp = 31;
  info.millivolts = 7400;
  EXPECT_EQ(
      bus_servo_state_table(info),
      "state       value\noffset      -4\nposition    512\ntemp        31\nmillivolts  7400\n");
}

TEST(ReadingTable, VoltsAreRoundedToTheNearestTenMillivolts) {
  EXPECT_EQ(voltage_text(7500), "7500 mV (7.50 V)");
  EXPECT_EQ(voltage_text(7404), "7404 mV (7.40 V)");
  EXPECT_EQ(voltage_text(7405), "7405 mV (7.41 V)");
  EXPECT_EQ(voltage_text(0), "0 mV (0.00 V)");
  EXPECT_EQ(voltage_text(65535), "65535 mV (65.54 V)");
}

}  // namespace
}  // namespace seqc::boards
