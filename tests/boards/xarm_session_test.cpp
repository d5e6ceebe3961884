// XarmSession against an emulated controller and against one that never answers: what a
// failure keeps, in place of the words the CLI puts around it.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>

#include "runtime/boards/recording_transport.hpp"
#include "runtime/boards/xarm_session.hpp"
#include "runtime/emulator/emulator_transport.hpp"
#include "runtime/emulator/xarm_emulator.hpp"
#include "runtime/upload/controller_link.hpp"
#include "tests/boards/board_test_util.hpp"

namespace seqc::boards {
namespace {

using test_support::silent;

using std::chrono::milliseconds;

struct Emulated {
  io::ManualClock clock;
  emu::XArmEmulator controller{emu::XArmConfig{}};
  emu::EmulatorTransport transport{controller, clock};
  upload::ControllerLink link{transport, clock};
};

TEST(XarmSession, AsksAndTells) {
  Emulated e;
  XarmSession s(e.link, milliseconds(200));
  const auto battery = s.ask<lsc::BatteryVoltage>(lsc::GetBatteryVoltage{}, "the battery voltage");
  ASSERT_TRUE(battery.has_value());
  EXPECT_GT(battery->millivolts, 0);
  EXPECT_TRUE(s.tell(lsc::GroupStop{}));
  EXPECT_FALSE(s.failure().has_value());
}

TEST(XarmSession, AnUnansweredAskIsNoReply) {
  io::ManualClock clock;
  AcknowledgingTransport dead(clock, silent);
  upload::ControllerLink link(dead, clock);
  XarmSession s(link, milliseconds(200));
  EXPECT_FALSE(s.ask<lsc::BatteryVoltage>(lsc::GetBatteryVoltage{}, "the battery voltage"));
  ASSERT_TRUE(s.failure().has_value());
  EXPECT_EQ(s.failure()->failure, Failure::NoReply);
  EXPECT_EQ(s.failure()->awaiting, "the battery voltage");
  EXPECT_EQ(clock.now(), io::TimePoint{} + milliseconds(200));
}

TEST(XarmSession, AnUnansweredTellIsUnconfirmedAfterTwoChecks) {
  io::ManualClock clock;
  AcknowledgingTransport dead(clock, silent);
  upload::ControllerLink link(dead, clock);
  XarmSession s(link, milliseconds(200));
  EXPECT_FALSE(s.tell(lsc::GroupStop{}));
  ASSERT_TRUE(s.failure().has_value());
  EXPECT_EQ(s.failure()->failure, Failure::Unconfirmed);
  EXPECT_EQ(s.failure()->request, "GroupStop");
  EXPECT_EQ(s.failure()->attempts, 2);
  // GroupStop, then the battery check twice.
  ASSERT_EQ(dead.writes().size(), 3u);
  EXPECT_EQ(to_hex(dead.writes()[0]), "55 55 02 07");
  EXPECT_EQ(to_hex(dead.writes()[1]), "55 55 02 0f");
  EXPECT_EQ(to_hex(dead.writes()[2]), "55 55 02 0f");
  EXPECT_EQ(clock.now(), io::TimePoint{} + milliseconds(400));
  // The first failure stays; nothing more is sent.
  EXPECT_FALSE(s.tell(lsc::GroupStop{}));
  EXPECT_EQ(dead.writes().size(), 3u);
}

TEST(XarmSession, InterruptedBeforeSendingSendsNothing) {
  io::ManualClock clock;
  AcknowledgingTransport dead(clock, silent);
  std::atomic<bool> interrupted{true};
  upload::ControllerLink link(dead, clock, &interrupted);
  XarmSession s(link, milliseconds(200));
  EXPECT_FALSE(s.tell(lsc::GroupStop{}));
  ASSERT_TRUE(s.failure().has_value());
  EXPECT_EQ(s.failure()->failure, Failure::Interrupted);
  EXPECT_EQ(s.failure()->awaiting, "");
  EXPECT_TRUE(dead.writes().empty());
}

}  // namespace
}  // namespace seqc::boards
