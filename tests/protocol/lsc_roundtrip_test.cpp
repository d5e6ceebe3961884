// decode(encode(x)) == x for every servo controller message, at typical values and edges.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "protocol/lsc/lsc_frame.hpp"
#include "protocol/lsc/lsc_messages.hpp"

namespace seqc::lsc {
namespace {

std::vector<std::uint8_t> ids(std::size_t n, std::uint8_t first = 0) {
  std::vector<std::uint8_t> out;
  for (std::size_t i = 0; i < n; ++i) out.push_back(static_cast<std::uint8_t>(first + i));
  return out;
}

std::vector<Request> sample_requests() {
  MultiServoMove big;
  big.time_ms = 0xffff;
  for (int i = 0; i < 83; ++i) {  // the most that fit: 3 + 3*83 = 252 data bytes
    big.servos.push_back({static_cast<std::uint8_t>(i),
                          i % 2 ? std::optional<std::uint16_t>() : std::uint16_t{0xfeff}});
  }
  GroupDownloadAction widest{3, 3, 254, 30000, {}};
  for (int i = 0; i < 82; ++i) {  // 7 + 3*82 = 253 data bytes, a full frame
    widest.servos.push_back({static_cast<std::uint8_t>(i), 0xff00});
  }
  BusServoLimits extremes{0xffff, 0, 0xffff, 0, 0xffff, 1, 7};
  return {
      MultiServoMove{},
      MultiServoMove{0, {{0, 0}}},
      MultiServoMove{20, {{255, 0xffff}, {1, std::nullopt}}},
      big,
      GroupDownloadOpen{0, {1}},
      GroupDownloadOpen{255, {255, 255, 255, 255}},
      GroupDownloadSize{0, 0, 1},
      GroupDownloadSize{255, 3, 255},
      GroupDownloadBlocks{0, 1},
      GroupDownloadBlocks{9, 4},
      GroupDownloadAction{0, 0, 0, 20, {{1, 500}}},
      GroupDownloadAction{1, 0, 0, 0, {}},
      widest,
      GroupDownloadClose{0},
      GroupDownloadClose{255},
      GroupRun{0, 0},
      GroupRun{255, 0xffff},
      GroupStop{},
      GroupErase{0},
      GroupErase{kAllGroups},
      GroupSpeed{kAllGroups, 0},
      GroupSpeed{0, 0xffff},
      GetBatteryVoltage{},
      MultiServoOff{},
      MultiServoOff{ids(252)},
      ServoPositionRead{{255}},
      ServoPositionRead{ids(252, 4)},
      ServoOffsetWrite{{0, 1}},
      ServoOffsetRead{ids(6, 1)},
      ServoOffsetAdjust{0, -32768},
      ServoOffsetAdjust{255, 32767},
      ServoOffsetAdjust{1, 0},
      ServoSpeed{0, ServoMode::Servo, 0},
      ServoSpeed{255, ServoMode::Motor, 0xffff},
      BusServoInfoWrite{},
      BusServoInfoWrite{255, extremes},
      BusServoInfoRead{},
  };
}

std::vector<Reply> sample_replies() {
  std::vector<ServoTarget> positions;
  for (int i = 0; i < 84; ++i) {  // 1 + 3*84 = 253 data bytes
    positions.push_back({static_cast<std::uint8_t>(i), static_cast<std::uint16_t>(i * 700)});
  }
  std::vector<ServoOffsets::Entry> offsets;
  for (int i = 0; i < 126; ++i) {  // 1 + 2*126 = 253 data bytes
    offsets.push_back({static_cast<std::uint8_t>(i), static_cast<std::int8_t>(i - 64)});
  }
  BusServoInfo info;
  info.id = 255;
  info.limits = BusServoLimits{1, 2, 3, 4, 5, 0, 5};
  info.offset = -128;
  info.position = 0xffff;
  info.temp = 255;
  info.millivolts = 0xffff;
  return {
      GroupDownloadAck{1, 0},
      GroupDownloadAck{5, 255},
      GroupStarted{0, 0},
      GroupStarted{255, 0xffff},
      GroupStopped{},
      GroupStopped{GroupStopped::Detail{0, 0}},
      GroupStopped{GroupStopped::Detail{255, 0xffff}},
      GroupFinished{0, 0},
      GroupFinished{7, 0xffff},
      GroupErased{},
      BatteryVoltage{0},
      BatteryVoltage{0xffff},
      ServoPositions{},
      ServoPositions{positions},
      ServoOffsets{},
      ServoOffsets{{{1, 127}, {2, -128}}},
      ServoOffsets{offsets},
      BusServoInfo{},
      info,
  };
}

TEST(LscRoundTrip, EveryRequest) {
  std::vector<bool> seen(std::variant_size_v<Request>, false);
  for (const Request& r : sample_requests()) {
    seen[r.index()] = true;
    auto bytes = encode_serial(r);
    ASSERT_TRUE(bytes.ok()) << describe(r) << ": " << bytes.error().message;
    auto frame = decode_serial(*bytes);
    ASSERT_TRUE(frame.ok()) << describe(r);
    auto back = decode_request(*frame);
    ASSERT_TRUE(back.ok()) << describe(r) << ": " << back.error().message;
    EXPECT_EQ(*back, r) << describe(r);
  }
  for (std::size_t i = 0; i < seen.size(); ++i) EXPECT_TRUE(seen[i]) << "request " << i;
}

TEST(LscRoundTrip, EveryReply) {
  std::vector<bool> seen(std::variant_size_v<Reply>, false);
  for (const Reply& r : sample_replies()) {
    seen[r.index()] = true;
    auto bytes = encode_serial(r);
    ASSERT_TRUE(bytes.ok()) << describe(r) << ": " << bytes.error().message;
    auto frame = decode_serial(*bytes);
    ASSERT_TRUE(frame.ok()) << describe(r);
    auto back = decode_reply(*frame);
    ASSERT_TRUE(back.ok()) << describe(r) << ": " << back.error().message;
    EXPECT_EQ(*back, r) << describe(r);
  }
  for (std::size_t i = 0; i < seen.size(); ++i) EXPECT_TRUE(seen[i]) << "reply " << i;
}

TEST(LscRoundTrip, ThroughHidReports) {
  for (const Request& r : sample_requests()) {
    auto frame = encode(r);
    ASSERT_TRUE(frame.ok());
    auto report = encode_hid_report(*frame);
    if (frame->data.size() > kHidMaxData) {
      EXPECT_FALSE(report.ok()) << describe(r);
      continue;
    }
    ASSERT_TRUE(report.ok()) << describe(r);
    // The host writes report id + 64 bytes; the device sees the 64 bytes after the id.
    auto back = decode_hid_report(ByteView(*report).subspan(1));
    ASSERT_TRUE(back.ok()) << describe(r) << ": " << back.error().message;
    EXPECT_EQ(*back, *frame);
  }
}

}  // namespace
}  // namespace seqc::lsc
