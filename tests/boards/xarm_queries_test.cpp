// The xArm family's multi-request readings and settings (runtime/boards/xarm_queries.hpp)
// against a scripted controller whose replies, like the expected requests, are written by hand
// from docs/protocol/servo-controller.md.
#include <gtest/gtest.h>

#include <chrono>

#include "runtime/boards/recording_transport.hpp"
#include "runtime/boards/xarm_queries.hpp"
#include "runtime/upload/controller_link.hpp"

namespace seqc::boards {
namespace {

using std::chrono::milliseconds;

Bytes hex(std::string_view text) { return *parse_hex(text); }

// ServoPositionRead of 3, 1, 9 is answered for 1 (300 = 0x012c) and 3 (500 = 0x01f4), in that
// order; servo 9 is not on the bus. BusServoInfoRead is answered for servo 5: positions
// 100..1000, 4500..12000 mV, 85 C, LED on, warnings overheat+overposition (0x05), offset -2,
// at 500, 32 C, 7400 mV. The battery check after a write is answered with 7400 mV.
Bytes controller(ByteView request) {
  const std::string r = to_hex(request);
  if (r == "55 55 06 15 03 03 01 09") return hex("55 55 09 15 02 01 2c 01 03 f4 01");
  if (r == "55 55 02 1c") {
    return hex("55 55 15 1c 05 64 00 e8 03 94 11 e0 2e 55 00 00 05 fe f4 01 20 e8 1c");
  }
  if (r == "55 55 02 0f") return hex("55 55 04 0f e8 1c");
  return {};
}

struct Scripted {
  io::ManualClock clock;
  AcknowledgingTransport port{clock, controller};
  upload::ControllerLink link{port, clock};
  XarmSession session{link, milliseconds(200)};
};

TEST(XarmQueries, PositionsComeInTheOrderAskedAndOnlyForServosThatAnswered) {
  Scripted s;
  const auto answered = read_positions(s.session, {3, 1, 9});
  ASSERT_TRUE(answered.has_value());
  EXPECT_EQ(*answered, (std::vector<lsc::ServoTarget>{{3, 500}, {1, 300}}));
  ASSERT_EQ(s.port.writes().size(), 1u);
  EXPECT_EQ(to_hex(s.port.writes()[0]), "55 55 06 15 03 03 01 09");
}

TEST(XarmQueries, PositionsFailWithTheSession) {
  Scripted s;
  EXPECT_FALSE(read_positions(s.session, {2}).has_value());
  ASSERT_TRUE(s.session.failure().has_value());
  EXPECT_EQ(s.session.failure()->failure, Failure::NoReply);
  EXPECT_EQ(s.session.failure()->awaiting, "the positions");
}

TEST(XarmQueries, OnlyBusServosReportPositions) {
  compiler::RobotInfo bus;
  bus.servos = {{"a", 1, 0, 1000, 500, {}, {}},
                {"b", 2, 0, 1000, 500, {}, {}},
                {"c", 3, 0, 1000, 500, {}, {}}};
  EXPECT_EQ(readable_servos(bus), (std::vector<std::uint8_t>{1, 2, 3}));
  bus.highest_defined_id = 2;  // the file's robot section names servos up to 2
  EXPECT_EQ(readable_servos(bus), (std::vector<std::uint8_t>{1, 2}));
  compiler::RobotInfo pwm;
  pwm.servos = {{"a", 1, 500, 2500, 1500, {}, {}}};
  EXPECT_TRUE(readable_servos(pwm).empty());
  EXPECT_TRUE(readable_servos(compiler::RobotInfo{}).empty());
}

TEST(XarmQueries, LedWarningNames) {
  EXPECT_EQ(led_warning_names(0), "none");
  EXPECT_EQ(led_warning_names(0x05), "overheat,overposition");
  EXPECT_EQ(led_warning_names(0x02), "overvoltage");
  EXPECT_EQ(led_warning_names(0x09), "overheat,bits 9");
  EXPECT_EQ(*parse_led_warnings("none"), 0);
  EXPECT_EQ(*parse_led_warnings("overposition,overheat"), 0x05);
  EXPECT_EQ(*parse_led_warnings("overvoltage"), 0x02);
  EXPECT_EQ(parse_led_warnings("overheat,hot").error().message,
            "unknown warning 'hot'; use a comma list of overheat, overvoltage, overposition, or "
            "none");
}

TEST(XarmQueries, ChangesKeepTheFieldsNotGiven) {
  BusServoChanges c;
  c.position_max = 900;
  c.led_status = 1;
  EXPECT_FALSE(c.complete());
  const lsc::BusServoLimits current{100, 1000, 4500, 12000, 85, 0, 0x05};
  const lsc::BusServoInfoWrite w = c.applied_to(5, current);
  EXPECT_EQ(w.servo, 5);
  EXPECT_EQ(w.limits, (lsc::BusServoLimits{100, 900, 4500, 12000, 85, 1, 0x05}));
  c.servo = 7;
  EXPECT_EQ(c.applied_to(5, current).servo, 7);
  c.position_min = c.millivolts_min = c.millivolts_max = c.temp_max = 1;
  c.led_warning = 0;
  EXPECT_TRUE(c.complete());
}

TEST(XarmQueries, ConflictingLimits) {
  EXPECT_EQ(conflict_in({100, 1000, 4500, 12000, 85, 0, 0}), LimitConflict::None);
  EXPECT_EQ(conflict_in({500, 500, 4500, 4500, 85, 0, 0}), LimitConflict::None);
  EXPECT_EQ(conflict_in({501, 500, 4500, 12000, 85, 0, 0}), LimitConflict::Position);
  EXPECT_EQ(conflict_in({100, 1000, 12001, 12000, 85, 0, 0}), LimitConflict::Voltage);
  EXPECT_EQ(conflict_text({501, 500, 4500, 12000, 85, 0, 0}),
            "position-min 501 is above position-max 500");
  EXPECT_EQ(conflict_text({100, 1000, 12001, 12000, 85, 0, 0}),
            "millivolts-min 12001 is above millivolts-max 12000");
}

TEST(XarmQueries, EveryFieldGivenIsCheckedForConflictsBeforeAnyRead) {
  BusServoFields f;
  f.servo = 1;
  f.position_min = 100;
  f.position_max = 900;
  f.millivolts_min = 9000;
  f.millivolts_max = 8000;
  f.temp_max = 80;
  f.led = "on";
  f.led_warning = "none";
  EXPECT_EQ(checked_changes(f).error().message, "millivolts-min 9000 is above millivolts-max 8000");
  f.millivolts_max = 12000;
  EXPECT_TRUE(checked_changes(f));
  f.led_warning.reset();  // not complete: the servo's values may settle it
  f.millivolts_max = 8000;
  EXPECT_TRUE(checked_changes(f));
}

TEST(XarmQueries, APartialWriteReadsTheServoFirstAndKeepsItsOtherValues) {
  Scripted s;
  BusServoChanges c;
  c.position_max = 900;  // 0x0384
  const BusServoWrite w = write_bus_servo_info(s.session, c);
  EXPECT_TRUE(w.written);
  EXPECT_EQ(w.conflict, LimitConflict::None);
  EXPECT_EQ(w.write.servo, 5);
  // The read, the write with servo 5's other values, then the battery check that confirms it.
  ASSERT_EQ(s.port.writes().size(), 3u);
  EXPECT_EQ(to_hex(s.port.writes()[0]), "55 55 02 1c");
  EXPECT_EQ(to_hex(s.port.writes()[1]), "55 55 0f 1b 05 64 00 84 03 94 11 e0 2e 55 00 00 05");
  EXPECT_EQ(to_hex(s.port.writes()[2]), "55 55 02 0f");
}

TEST(XarmQueries, AWriteWhoseMergedLimitsConflictWritesNothing) {
  Scripted s;
  BusServoChanges c;
  c.position_min = 1200;  // above the servo's position-max of 1000
  const BusServoWrite w = write_bus_servo_info(s.session, c);
  EXPECT_FALSE(w.written);
  EXPECT_EQ(w.conflict, LimitConflict::Position);
  EXPECT_EQ(w.write.limits.position_min, 1200);
  EXPECT_EQ(w.write.limits.position_max, 1000);
  ASSERT_EQ(s.port.writes().size(), 1u);
  EXPECT_EQ(to_hex(s.port.writes()[0]), "55 55 02 1c");
  EXPECT_FALSE(s.session.failure().has_value());
}

TEST(XarmQueries, ACompleteWriteDoesNotReadFirst) {
  Scripted s;
  BusServoChanges c;
  c.servo = 2;
  c.position_min = 0;
  c.position_max = 1000;    // e8 03
  c.millivolts_min = 5000;  // 88 13
  c.millivolts_max = 8400;  // d0 20
  c.temp_max = 70;          // 46 00
  c.led_status = 1;
  c.led_warning = 0x07;
  const BusServoWrite w = write_bus_servo_info(s.session, c);
  EXPECT_TRUE(w.written);
  ASSERT_EQ(s.port.writes().size(), 2u);
  EXPECT_EQ(to_hex(s.port.writes()[0]), "55 55 0f 1b 02 00 00 e8 03 88 13 d0 20 46 00 01 07");
  EXPECT_EQ(to_hex(s.port.writes()[1]), "55 55 02 0f");
}

}  // namespace
}  // namespace seqc::boards
