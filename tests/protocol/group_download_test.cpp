// Pins every reading of the GroupDownload table (group_download.cpp) to exact bytes, written
// by hand. Plans use group 1 and action i = 1000 ms, servo 1 at position 1000 + i, so every
// action frame is 55 55 0C 05 04 01 <block> <index> 0B E8 03 01 <posLo> <posHi>.
#include "protocol/lsc/group_download.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "tests/protocol/wire_test_util.hpp"

namespace seqc::lsc {
namespace {

using test::hex;
using test::norm;

std::vector<GroupAction> actions(std::size_t n) {
  std::vector<GroupAction> out;
  for (std::size_t i = 0; i < n; ++i) {
    out.push_back(GroupAction{1000, {{1, static_cast<std::uint16_t>(1000 + i)}}});
  }
  return out;
}

// The plan for `n` actions as serial hex, one string per request in send order.
std::vector<std::string> wire_plan(std::size_t n) {
  const auto acts = actions(n);
  auto plan = plan_group_download(1, acts);
  EXPECT_TRUE(plan.ok()) << (plan.ok() ? "" : plan.error().message);
  std::vector<std::string> out;
  if (!plan.ok()) return out;
  for (const Request& r : *plan) {
    auto bytes = encode_serial(r);
    EXPECT_TRUE(bytes.ok()) << describe(r);
    out.push_back(bytes.ok() ? to_hex(*bytes) : "error");
  }
  return out;
}

TEST(GroupDownload, OneAction) {
  const std::vector<std::string> expected = {
      norm("55 55 05 05 01 01 01"),                       // open: one block of 1
      norm("55 55 07 05 02 01 00 01 00"),                 // size of block 0
      norm("55 55 06 05 03 01 00 00"),                    // blocks: 00, then block 0
      norm("55 55 0C 05 04 01 00 00 0B E8 03 01 E8 03"),  // action 0, position 1000
      norm("55 55 04 05 05 01"),                          // close
  };
  EXPECT_EQ(wire_plan(1), expected);
}

TEST(GroupDownload, OneFullBlock) {
  const auto w = wire_plan(255);
  ASSERT_EQ(w.size(), 1u + 1 + 1 + 255 + 1);
  EXPECT_EQ(w[0], norm("55 55 05 05 01 01 FF"));
  EXPECT_EQ(w[1], norm("55 55 07 05 02 01 00 FF 00"));
  EXPECT_EQ(w[2], norm("55 55 06 05 03 01 00 00"));
  EXPECT_EQ(w[3], norm("55 55 0C 05 04 01 00 00 0B E8 03 01 E8 03"));
  EXPECT_EQ(w[3 + 254], norm("55 55 0C 05 04 01 00 FE 0B E8 03 01 E6 04"));  // 1254
  EXPECT_EQ(w.back(), norm("55 55 04 05 05 01"));
}

TEST(GroupDownload, TwoFiftySixActionsStartASecondBlock) {
  const auto w = wire_plan(256);
  ASSERT_EQ(w.size(), 1u + 2 + 1 + 256 + 1);
  EXPECT_EQ(w[0], norm("55 55 06 05 01 01 FF 01"));
  EXPECT_EQ(w[1], norm("55 55 07 05 02 01 00 FF 00"));
  EXPECT_EQ(w[2], norm("55 55 07 05 02 01 01 01 00"));
  EXPECT_EQ(w[3], norm("55 55 07 05 03 01 00 00 01"));
  EXPECT_EQ(w[4 + 254], norm("55 55 0C 05 04 01 00 FE 0B E8 03 01 E6 04"));  // action 254
  EXPECT_EQ(w[4 + 255], norm("55 55 0C 05 04 01 01 00 0B E8 03 01 E7 04"));  // action 255
  EXPECT_EQ(w.back(), norm("55 55 04 05 05 01"));
}

TEST(GroupDownload, TwoFullBlocks) {
  const auto w = wire_plan(510);
  ASSERT_EQ(w.size(), 1u + 2 + 1 + 510 + 1);
  EXPECT_EQ(w[0], norm("55 55 06 05 01 01 FF FF"));
  EXPECT_EQ(w[1], norm("55 55 07 05 02 01 00 FF 00"));
  EXPECT_EQ(w[2], norm("55 55 07 05 02 01 01 FF 00"));
  EXPECT_EQ(w[3], norm("55 55 07 05 03 01 00 00 01"));
  EXPECT_EQ(w[4 + 509], norm("55 55 0C 05 04 01 01 FE 0B E8 03 01 E5 05"));  // 1509
}

TEST(GroupDownload, ThreeFullBlocks) {
  const auto w = wire_plan(765);
  ASSERT_EQ(w.size(), 1u + 3 + 1 + 765 + 1);
  EXPECT_EQ(w[0], norm("55 55 07 05 01 01 FF FF FF"));
  EXPECT_EQ(w[3], norm("55 55 07 05 02 01 02 FF 00"));
  EXPECT_EQ(w[4], norm("55 55 08 05 03 01 00 00 01 02"));
  EXPECT_EQ(w[5 + 510], norm("55 55 0C 05 04 01 02 00 0B E8 03 01 E6 05"));  // 1510
  EXPECT_EQ(w[5 + 764], norm("55 55 0C 05 04 01 02 FE 0B E8 03 01 E4 06"));  // 1764
}

TEST(GroupDownload, FourFullBlocksIsTheMaximum) {
  const auto w = wire_plan(1020);
  ASSERT_EQ(w.size(), 1u + 4 + 1 + 1020 + 1);
  EXPECT_EQ(w[0], norm("55 55 08 05 01 01 FF FF FF FF"));
  EXPECT_EQ(w[1], norm("55 55 07 05 02 01 00 FF 00"));
  EXPECT_EQ(w[2], norm("55 55 07 05 02 01 01 FF 00"));
  EXPECT_EQ(w[3], norm("55 55 07 05 02 01 02 FF 00"));
  EXPECT_EQ(w[4], norm("55 55 07 05 02 01 03 FF 00"));
  EXPECT_EQ(w[5], norm("55 55 09 05 03 01 00 00 01 02 03"));
  EXPECT_EQ(w[6 + 765], norm("55 55 0C 05 04 01 03 00 0B E8 03 01 E5 06"));   // 1765
  EXPECT_EQ(w[6 + 1019], norm("55 55 0C 05 04 01 03 FE 0B E8 03 01 E3 07"));  // 2019
  EXPECT_EQ(w.back(), norm("55 55 04 05 05 01"));
}

TEST(GroupDownload, PartialLastBlock) {
  const auto w = wire_plan(600);  // 255 + 255 + 90
  EXPECT_EQ(w[0], norm("55 55 07 05 01 01 FF FF 5A"));
  EXPECT_EQ(w[3], norm("55 55 07 05 02 01 02 5A 00"));
}

TEST(GroupDownload, ZeroOrTooManyActionsAreRejected) {
  EXPECT_FALSE(plan_group_download(1, actions(0)).ok());
  EXPECT_FALSE(plan_group_download(1, actions(1021)).ok());
}

TEST(GroupDownload, ActionTimeAndWidthAreChecked) {
  std::vector<GroupAction> a = actions(3);
  a[1].time_ms = 19;
  auto plan = plan_group_download(0, a);
  ASSERT_FALSE(plan.ok());
  EXPECT_NE(plan.error().message.find("action 2 of 3"), std::string::npos);
  a[1].time_ms = 30001;
  EXPECT_FALSE(plan_group_download(0, a).ok());
  a[1].time_ms = 30000;
  EXPECT_TRUE(plan_group_download(0, a).ok());
  a[1].servos.assign(83, ServoTarget{1, 1500});  // 7 + 3*83 = 256 data bytes
  EXPECT_FALSE(plan_group_download(0, a).ok());
  a[1].servos.assign(82, ServoTarget{1, 1500});
  EXPECT_TRUE(plan_group_download(0, a).ok());
}

TEST(GroupDownload, SlotOf) {
  const std::pair<std::size_t, std::pair<int, int>> cases[] = {
      {0, {0, 0}},   {254, {0, 254}}, {255, {1, 0}},    {509, {1, 254}},
      {510, {2, 0}}, {765, {3, 0}},   {1019, {3, 254}},
  };
  for (const auto& [n, want] : cases) {
    const ActionSlot s = slot_of(n);
    EXPECT_EQ(s.block, want.first) << n;
    EXPECT_EQ(s.index, want.second) << n;
  }
}

TEST(GroupDownload, StepNumbers) {
  auto plan = plan_group_download(1, actions(256));
  ASSERT_TRUE(plan.ok());
  std::vector<int> steps;
  for (const Request& r : *plan) steps.push_back(group_download_step(r));
  std::vector<int> expected = {1, 2, 2, 3};
  expected.insert(expected.end(), 256, 4);
  expected.push_back(5);
  EXPECT_EQ(steps, expected);
  EXPECT_EQ(group_download_step(Request{GroupRun{0, 1}}), 0);
  EXPECT_EQ(group_download_step(Request{GetBatteryVoltage{}}), 0);
}

TEST(GroupDownload, AcknowledgementsAndARefusal) {
  auto ack = decode_ack(Frame{0x05, hex("03 00")});
  ASSERT_TRUE(ack.ok());
  EXPECT_EQ(ack->step, 3);
  EXPECT_TRUE(ack->accepted());

  auto refusal = decode_ack(Frame{0x05, hex("04 01")});
  ASSERT_TRUE(refusal.ok());
  EXPECT_EQ(refusal->step, 4);
  EXPECT_FALSE(refusal->accepted());

  EXPECT_EQ(to_hex(*encode_serial(encode_ack(GroupDownloadAck{5, 0}))), norm("55 55 04 05 05 00"));
  EXPECT_FALSE(decode_ack(Frame{0x05, hex("06 00")}).ok());  // no step 6
  EXPECT_FALSE(decode_ack(Frame{0x05, hex("00 00")}).ok());
  EXPECT_FALSE(decode_ack(Frame{0x05, hex("01")}).ok());
  EXPECT_FALSE(decode_ack(Frame{0x05, hex("01 00 00")}).ok());
  EXPECT_FALSE(decode_ack(Frame{0x06, hex("01 00")}).ok());
}

TEST(GroupDownload, EveryPlannedRequestDecodesBackToItself) {
  auto plan = plan_group_download(7, actions(600));
  ASSERT_TRUE(plan.ok());
  for (const Request& r : *plan) {
    auto frame = encode(r);
    ASSERT_TRUE(frame.ok());
    auto back = decode_group_download(*frame);
    ASSERT_TRUE(back.ok()) << describe(r) << ": " << back.error().message;
    EXPECT_EQ(*back, r);
  }
}

}  // namespace
}  // namespace seqc::lsc

namespace seqc::lsc {
namespace {

TEST(GroupDownload, ActionFrameSizeAndTheHidLimit) {
  // 55 55 LEN 05 04 G b i 0B tLo tHi = 11 bytes, then 3 per servo: 17 servos make 62 bytes, one
  // 64-byte HID report; 18 make 65, one too many.
  EXPECT_EQ(action_frame_bytes(17), 62u);
  EXPECT_EQ(action_frame_bytes(18), 65u);
  EXPECT_EQ(kHidMaxActionServos, 17u);
  GroupDownloadAction wide{1, 0, 0, 1000, {}};
  for (std::uint8_t id = 1; id <= 18; ++id) wide.servos.push_back({id, 500});
  auto frame = encode_step(wide);
  ASSERT_TRUE(frame.ok()) << frame.error().message;
  auto serial = encode_serial(*frame);
  ASSERT_TRUE(serial.ok());
  EXPECT_EQ(serial->size(), 65u);
  EXPECT_FALSE(encode_hid_report(*frame).ok());
  wide.servos.pop_back();
  auto fits = encode_step(wide);
  ASSERT_TRUE(fits.ok());
  EXPECT_EQ(encode_serial(*fits)->size(), 62u);
  EXPECT_TRUE(encode_hid_report(*fits).ok());
}

}  // namespace
}  // namespace seqc::lsc
