// Golden wire vectors for every servo controller request and reply, written by hand from
// docs/protocol/servo-controller.md (little-endian ushort). Each is checked both
// ways: value -> bytes and bytes -> value.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "protocol/lsc/lsc_frame.hpp"
#include "protocol/lsc/lsc_messages.hpp"
#include "tests/protocol/wire_test_util.hpp"

namespace seqc::lsc {
namespace {

using test::hex;
using test::hex_or_error;
using test::norm;

struct RequestVector {
  const char* name;
  Request value;
  const char* wire;
};

struct ReplyVector {
  const char* name;
  Reply value;
  const char* wire;
};

BusServoLimits sample_limits() {
  BusServoLimits l;
  l.position_min = 0;
  l.position_max = 1000;
  l.millivolts_min = 4500;
  l.millivolts_max = 12000;
  l.temp_max = 85;
  l.led_status = 1;
  l.led_warning = 7;
  return l;
}

std::vector<RequestVector> request_vectors() {
  return {
      // The vendor document's example: servo 1 to 2000 in 1000 ms.
      {"MultiServoMove vendor example", MultiServoMove{1000, {{1, 2000}}},
       "55 55 08 03 01 E8 03 01 D0 07"},
      {"MultiServoMove with a servo left alone",
       MultiServoMove{500, {{1, 1500}, {2, std::nullopt}}},
       "55 55 0B 03 02 F4 01 01 DC 05 02 00 FF"},
      {"GroupDownloadOpen", GroupDownloadOpen{0, {255, 1}}, "55 55 06 05 01 00 FF 01"},
      {"GroupDownloadSize", GroupDownloadSize{0, 1, 1}, "55 55 07 05 02 00 01 01 00"},
      {"GroupDownloadBlocks", GroupDownloadBlocks{0, 2}, "55 55 07 05 03 00 00 00 01"},
      {"GroupDownloadAction", GroupDownloadAction{0, 1, 0, 1000, {{1, 2000}}},
       "55 55 0C 05 04 00 01 00 0B E8 03 01 D0 07"},
      {"GroupDownloadClose", GroupDownloadClose{0}, "55 55 04 05 05 00"},
      {"GroupRun once", GroupRun{2, 1}, "55 55 05 06 02 01 00"},
      {"GroupRun forever", GroupRun{0, 0}, "55 55 05 06 00 00 00"},
      {"GroupStop", GroupStop{}, "55 55 02 07"},
      {"GroupErase one", GroupErase{3}, "55 55 03 08 03"},
      {"GroupErase all", GroupErase{kAllGroups}, "55 55 03 08 FF"},
      {"GroupSpeed", GroupSpeed{1, 200}, "55 55 05 0B 01 C8 00"},
      {"GetBatteryVoltage", GetBatteryVoltage{}, "55 55 02 0F"},
      {"MultiServoOff", MultiServoOff{{1, 2, 3}}, "55 55 06 14 03 01 02 03"},
      {"ServoPositionRead", ServoPositionRead{{1, 2}}, "55 55 05 15 02 01 02"},
      {"ServoOffsetWrite", ServoOffsetWrite{{6}}, "55 55 04 16 01 06"},
      {"ServoOffsetRead", ServoOffsetRead{{1, 6}}, "55 55 05 17 02 01 06"},
      {"ServoOffsetAdjust", ServoOffsetAdjust{3, -20}, "55 55 05 18 03 EC FF"},
      {"ServoSpeed", ServoSpeed{1, ServoMode::Motor, 500}, "55 55 06 1A 01 01 F4 01"},
      {"BusServoInfoWrite", BusServoInfoWrite{1, sample_limits()},
       "55 55 0F 1B 01 00 00 E8 03 94 11 E0 2E 55 00 01 07"},
      {"BusServoInfoRead", BusServoInfoRead{}, "55 55 02 1C"},
  };
}

std::vector<ReplyVector> reply_vectors() {
  BusServoInfo info;
  info.id = 1;
  info.limits = sample_limits();
  info.offset = -2;
  info.position = 500;
  info.temp = 40;
  info.millivolts = 7400;
  return {
      {"GroupDownloadAck accepted", GroupDownloadAck{1, 0}, "55 55 04 05 01 00"},
      {"GroupDownloadAck refused", GroupDownloadAck{4, 1}, "55 55 04 05 04 01"},
      {"GroupStarted", GroupStarted{2, 1}, "55 55 05 06 02 01 00"},
      {"GroupStopped without data", GroupStopped{}, "55 55 02 07"},
      {"GroupStopped with data", GroupStopped{GroupStopped::Detail{2, 3}}, "55 55 05 07 02 03 00"},
      {"GroupFinished", GroupFinished{2, 1}, "55 55 05 08 02 01 00"},
      {"GroupErased (empty response)", GroupErased{}, "55 55 02 08"},
      // The vendor example: 4C 1D = 7500 mV.
      {"BatteryVoltage vendor example", BatteryVoltage{7500}, "55 55 04 0F 4C 1D"},
      {"ServoPositions", ServoPositions{{{1, 500}, {2, 1000}}}, "55 55 09 15 02 01 F4 01 02 E8 03"},
      {"ServoOffsets", ServoOffsets{{{1, -3}, {2, 5}}}, "55 55 07 17 02 01 FD 02 05"},
      {"BusServoInfo", info,
       "55 55 15 1C 01 00 00 E8 03 94 11 E0 2E 55 00 01 07 FE F4 01 28 E8 1C"},
  };
}

TEST(LscGolden, RequestsEncodeToHandWrittenBytes) {
  for (const auto& v : request_vectors()) {
    EXPECT_EQ(hex_or_error(encode_serial(v.value)), norm(v.wire)) << v.name;
  }
}

TEST(LscGolden, HandWrittenRequestBytesDecode) {
  for (const auto& v : request_vectors()) {
    auto frame = decode_serial(hex(v.wire));
    ASSERT_TRUE(frame.ok()) << v.name << ": " << frame.error().message;
    auto request = decode_request(*frame);
    ASSERT_TRUE(request.ok()) << v.name << ": " << request.error().message;
    EXPECT_EQ(*request, v.value) << v.name;
  }
}

TEST(LscGolden, RepliesEncodeToHandWrittenBytes) {
  for (const auto& v : reply_vectors()) {
    EXPECT_EQ(hex_or_error(encode_serial(v.value)), norm(v.wire)) << v.name;
  }
}

TEST(LscGolden, HandWrittenReplyBytesDecode) {
  for (const auto& v : reply_vectors()) {
    auto frame = decode_serial(hex(v.wire));
    ASSERT_TRUE(frame.ok()) << v.name << ": " << frame.error().message;
    auto reply = decode_reply(*frame);
    ASSERT_TRUE(reply.ok()) << v.name << ": " << reply.error().message;
    EXPECT_EQ(*reply, v.value) << v.name;
  }
}

TEST(LscGolden, EveryRequestAndReplyTypeHasAVector) {
  std::vector<bool> requests(std::variant_size_v<Request>, false);
  for (const auto& v : request_vectors()) requests[v.value.index()] = true;
  for (std::size_t i = 0; i < requests.size(); ++i) EXPECT_TRUE(requests[i]) << "request " << i;
  std::vector<bool> replies(std::variant_size_v<Reply>, false);
  for (const auto& v : reply_vectors()) replies[v.value.index()] = true;
  for (std::size_t i = 0; i < replies.size(); ++i) EXPECT_TRUE(replies[i]) << "reply " << i;
}

TEST(LscGolden, HidReportOfTheBatteryRequest) {
  auto frame = encode(Request{GetBatteryVoltage{}});
  ASSERT_TRUE(frame.ok());
  auto report = encode_hid_report(*frame);
  ASSERT_TRUE(report.ok());
  Bytes expected = hex("00 55 55 02 0F");
  expected.resize(65, 0x00);
  EXPECT_EQ(to_hex(*report), to_hex(expected));
}

}  // namespace
}  // namespace seqc::lsc
