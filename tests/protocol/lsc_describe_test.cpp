// describe(): the one-line text people read in listings and traces, pinned exactly.
#include <gtest/gtest.h>

#include "protocol/lsc/lsc_messages.hpp"

namespace seqc::lsc {
namespace {

TEST(LscDescribe, Requests) {
  EXPECT_EQ(describe(Request{MultiServoMove{1000, {{1, 2000}, {2, std::nullopt}}}}),
            "MultiServoMove time_ms=1000 servos=[{id=1 position=2000} {id=2 position=none}]");
  EXPECT_EQ(describe(Request{GroupDownloadOpen{0, {255, 1}}}),
            "GroupDownloadOpen group=0 block_counts=[255 1]");
  EXPECT_EQ(describe(Request{GroupDownloadSize{0, 1, 1}}),
            "GroupDownloadSize group=0 block=1 count=1");
  EXPECT_EQ(describe(Request{GroupDownloadBlocks{0, 2}}),
            "GroupDownloadBlocks group=0 block_count=2");
  EXPECT_EQ(describe(Request{GroupDownloadAction{0, 1, 0, 1000, {{1, 2000}}}}),
            "GroupDownloadAction group=0 block=1 index=0 time_ms=1000 "
            "servos=[{id=1 position=2000}]");
  EXPECT_EQ(describe(Request{GroupDownloadClose{0}}), "GroupDownloadClose group=0");
  EXPECT_EQ(describe(Request{GroupRun{0, 1}}), "GroupRun group=0 times=1");
  EXPECT_EQ(describe(Request{GroupStop{}}), "GroupStop");
  EXPECT_EQ(describe(Request{GroupErase{kAllGroups}}), "GroupErase group=all");
  EXPECT_EQ(describe(Request{GroupErase{3}}), "GroupErase group=3");
  EXPECT_EQ(describe(Request{GroupSpeed{1, 200}}), "GroupSpeed group=1 percent=200");
  EXPECT_EQ(describe(Request{GetBatteryVoltage{}}), "GetBatteryVoltage");
  EXPECT_EQ(describe(Request{MultiServoOff{{1, 2, 3}}}), "MultiServoOff servos=[1 2 3]");
  EXPECT_EQ(describe(Request{ServoPositionRead{{1, 2}}}), "ServoPositionRead servos=[1 2]");
  EXPECT_EQ(describe(Request{ServoOffsetWrite{{6}}}), "ServoOffsetWrite servos=[6]");
  EXPECT_EQ(describe(Request{ServoOffsetRead{{}}}), "ServoOffsetRead servos=[]");
  EXPECT_EQ(describe(Request{ServoOffsetAdjust{3, -20}}), "ServoOffsetAdjust servo=3 offset=-20");
  EXPECT_EQ(describe(Request{ServoSpeed{1, ServoMode::Motor, 500}}),
            "ServoSpeed servo=1 mode=motor milliseconds=500");
  EXPECT_EQ(describe(Request{BusServoInfoWrite{1, BusServoLimits{0, 1000, 4500, 12000, 85, 1, 7}}}),
            "BusServoInfoWrite servo=1 position_min=0 position_max=1000 millivolts_min=4500 "
            "millivolts_max=12000 temp_max=85 led_status=1 led_warning=7");
  EXPECT_EQ(describe(Request{BusServoInfoRead{}}), "BusServoInfoRead");
}

TEST(LscDescribe, Replies) {
  EXPECT_EQ(describe(Reply{GroupDownloadAck{1, 0}}), "GroupDownloadAck step=1 status=0 (accepted)");
  EXPECT_EQ(describe(Reply{GroupDownloadAck{4, 2}}), "GroupDownloadAck step=4 status=2 (refused)");
  EXPECT_EQ(describe(Reply{GroupStarted{2, 1}}), "GroupStarted group=2 times=1");
  EXPECT_EQ(describe(Reply{GroupStopped{}}), "GroupStopped");
  EXPECT_EQ(describe(Reply{GroupStopped{GroupStopped::Detail{2, 3}}}),
            "GroupStopped group=2 times=3");
  EXPECT_EQ(describe(Reply{GroupFinished{2, 1}}), "GroupFinished group=2 times=1");
  EXPECT_EQ(describe(Reply{GroupErased{}}), "GroupErased");
  EXPECT_EQ(describe(Reply{BatteryVoltage{7500}}), "BatteryVoltage millivolts=7500");
  EXPECT_EQ(describe(Reply{ServoPositions{{{1, 500}, {2, 1000}}}}),
            "ServoPositions servos=[{id=1 position=500} {id=2 position=1000}]");
  EXPECT_EQ(describe(Reply{ServoOffsets{{{1, -3}, {2, 5}}}}),
            "ServoOffsets servos=[{id=1 offset=-3} {id=2 offset=5}]");
  BusServoInfo info;
  info.id = 1;
  info.limits = BusServoLimits{0, 1000, 4500, 12000, 85, 0, 1};
  info.offset = -2;
  info.position = 500;
  info.temp = 40;
  info.millivolts = 7400;
  EXPECT_EQ(describe(Reply{info}),
            "BusServoInfo id=1 position_min=0 position_max=1000 millivolts_min=4500 "
            "millivolts_max=12000 temp_max=85 led_status=0 led_warning=1 offset=-2 "
            "position=500 temp=40 millivolts=7400");
}

}  // namespace
}  // namespace seqc::lsc
