// Golden wire vectors for every LSC-6 dialect message, written by hand from the board's
// behaviour as docs/protocol/lsc-6.md describes it. Each is checked both ways.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "protocol/lsc6/lsc6_messages.hpp"
#include "tests/protocol/wire_test_util.hpp"

namespace seqc::lsc6 {
namespace {

using test::hex;
using test::hex_or_error;
using test::norm;

struct RequestVector {
  const char* name;
  Request value;
  const char* wire;
};

const std::vector<RequestVector>& request_vectors() {
  static const std::vector<RequestVector> v = {
      // LEN 8 = 2 + N + time(2) + 3; 1000 ms = e8 03, 1500 us = dc 05
      {"move one channel", Move{1000, {{1, 1500}}}, "55 55 08 03 01 e8 03 01 dc 05"},
      {"move three channels", Move{20, {{6, 500}, {2, 2500}, {3, 1234}}},
       "55 55 0e 03 03 14 00 06 f4 01 02 c4 09 03 d2 04"},
      {"run twice", Run{2, 2}, "55 55 05 06 02 02 00"},
      {"run forever", Run{0, 0}, "55 55 05 06 00 00 00"},
      {"run group 255 65535 times", Run{255, 65535}, "55 55 05 06 ff ff ff"},
      {"stop", Stop{}, "55 55 02 07"},
      {"erase every group", EraseAll{}, "55 55 02 08"},
      // G=1 TOTAL=3 IDX=0 N=2 t=500 (f4 01) {1 1500} {6 2500}: 12 data bytes, LEN 0e
      {"first action", DownloadAction{1, 3, 0, 500, {{1, 1500}, {6, 2500}}},
       "55 55 0e 19 01 03 00 02 f4 01 01 dc 05 06 c4 09"},
      {"last action", DownloadAction{255, 255, 254, 30000, {{4, 900}}},
       "55 55 0b 19 ff ff fe 01 30 75 04 84 03"},
      {"pause action", DownloadAction{0, 1, 0, 100, {}}, "55 55 08 19 00 01 00 00 64 00"},
  };
  return v;
}

TEST(Lsc6Golden, RequestsEncodeToTheHandWrittenBytes) {
  for (const auto& v : request_vectors()) {
    EXPECT_EQ(hex_or_error(encode_serial(v.value)), norm(v.wire)) << v.name;
  }
}

TEST(Lsc6Golden, HandWrittenRequestsDecode) {
  for (const auto& v : request_vectors()) {
    auto frame = lsc::decode_serial(hex(v.wire));
    ASSERT_TRUE(frame.ok()) << v.name;
    auto decoded = lsc6::decode_request(*frame);
    ASSERT_TRUE(decoded.ok()) << v.name << ": " << decoded.error().message;
    EXPECT_EQ(*decoded, v.value) << v.name;
  }
}

TEST(Lsc6Golden, EveryAnswerIsFourBytes) {
  const std::vector<std::pair<Reply, const char*>> answers = {
      {RunAccepted{}, "55 55 02 06"},
      {GroupFinished{}, "55 55 02 07"},
      {Erased{}, "55 55 02 08"},
      {ActionStored{}, "55 55 02 19"},
  };
  for (const auto& [reply, wire] : answers) {
    EXPECT_EQ(to_hex(encode_serial(reply)), norm(wire)) << describe(reply);
    auto frame = lsc::decode_serial(hex(wire));
    ASSERT_TRUE(frame.ok());
    auto decoded = lsc6::decode_reply(*frame);
    ASSERT_TRUE(decoded.ok()) << wire;
    EXPECT_EQ(*decoded, reply) << wire;
  }
}

TEST(Lsc6Golden, EraseIgnoresItsParameter) {
  // The board wipes every group whatever byte follows the command.
  auto decoded = lsc6::decode_request(*lsc::decode_serial(hex("55 55 03 08 05")));
  ASSERT_TRUE(decoded.ok());
  EXPECT_TRUE(std::holds_alternative<EraseAll>(*decoded));
}

TEST(Lsc6Golden, XarmRepliesAreNotLsc6Answers) {
  // 55 55 04 05 01 00 is an xArm download acknowledgement; the LSC-6 never sends data.
  EXPECT_FALSE(lsc6::decode_reply(*lsc::decode_serial(hex("55 55 04 05 01 00"))).ok());
  EXPECT_FALSE(lsc6::decode_reply(*lsc::decode_serial(hex("55 55 02 0f"))).ok());
}

TEST(Lsc6Range, RefusesWhatTheBoardWouldIgnoreOrChange) {
  EXPECT_NE(hex_or_error(encode_serial(Move{1000, {{0, 1500}}})).find("channel 0"),
            std::string::npos);
  EXPECT_NE(hex_or_error(encode_serial(Move{1000, {{7, 1500}}})).find("1..6"), std::string::npos);
  EXPECT_NE(hex_or_error(encode_serial(Move{1000, {{1, 499}}})).find("500..2500"),
            std::string::npos);
  EXPECT_NE(hex_or_error(encode_serial(Move{19, {{1, 1500}}})).find("20..30000"),
            std::string::npos);
  EXPECT_NE(hex_or_error(encode_serial(Move{30001, {{1, 1500}}})).find("20..30000"),
            std::string::npos);
  EXPECT_NE(hex_or_error(encode_serial(DownloadAction{0, 2, 2, 100, {{1, 1500}}})).find("index"),
            std::string::npos);
  std::vector<Target> nine;
  for (std::uint8_t c = 0; c < 9; ++c) nine.push_back({static_cast<std::uint8_t>(1 + c % 6), 1500});
  EXPECT_NE(hex_or_error(encode_serial(DownloadAction{0, 1, 0, 100, nine})).find("at most 8"),
            std::string::npos);
}

TEST(Lsc6Range, NeverWritesALenThatWedgesTheReceiver) {
  // 84 servos make 3 + 252 = 255 data bytes: LEN would pass 253.
  Move big{100, {}};
  for (int i = 0; i < 84; ++i) big.servos.push_back({1, 1500});
  EXPECT_EQ(hex_or_error(encode_serial(big)).rfind("error:", 0), 0u);
  Move wedging{100, {}};
  // 3 + 3 x 83 = 252 data bytes -> LEN 254: still refused.
  for (int i = 0; i < 83; ++i) wedging.servos.push_back({1, 1500});
  EXPECT_EQ(hex_or_error(encode_serial(wedging)).rfind("error:", 0), 0u);
  Move largest{100, {}};
  for (int i = 0; i < 82; ++i) largest.servos.push_back({1, 1500});  // 249 bytes, LEN 251
  auto bytes = encode_serial(largest);
  ASSERT_TRUE(bytes.ok());
  EXPECT_EQ((*bytes)[2], 251);
}

TEST(Lsc6Plan, StoresEachActionWithItsIndexAndTheTotal) {
  auto plan = plan_download(3, {{100, {{1, 1500}}}, {200, {{2, 600}}}});
  ASSERT_TRUE(plan.ok());
  ASSERT_EQ(plan->size(), 2u);
  EXPECT_EQ(hex_or_error(encode_serial((*plan)[0])),
            norm("55 55 0b 19 03 02 00 01 64 00 01 dc 05"));
  EXPECT_EQ(hex_or_error(encode_serial((*plan)[1])),
            norm("55 55 0b 19 03 02 01 01 c8 00 02 58 02"));
}

TEST(Lsc6Plan, RefusesMoreThan255ActionsAndMoreThan8Servos) {
  std::vector<PlannedAction> many(256, PlannedAction{100, {{1, 1500}}});
  auto plan = plan_download(0, many);
  ASSERT_FALSE(plan.ok());
  EXPECT_EQ(plan.error().message, "256 actions do not fit one LSC-6 group (at most 255)");
  PlannedAction wide{100, {}};
  for (int i = 0; i < 9; ++i) wide.servos.push_back({static_cast<std::uint8_t>(1 + i % 6), 1500});
  auto plan2 = plan_download(0, {PlannedAction{100, {{1, 1500}}}, wide});
  ASSERT_FALSE(plan2.ok());
  EXPECT_EQ(plan2.error().message,
            "action 2 moves 9 servos; the LSC-6 stops playing at an action with more than 8");
}

}  // namespace
}  // namespace seqc::lsc6
