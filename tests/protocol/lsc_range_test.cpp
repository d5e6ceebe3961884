// Out-of-range values and malformed data are errors: never wrapped, clamped or half-read.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "protocol/lsc/lsc_frame.hpp"
#include "protocol/lsc/lsc_messages.hpp"
#include "tests/protocol/wire_test_util.hpp"

namespace seqc::lsc {
namespace {

using test::hex;

bool encodes(const Request& r) { return encode(r).ok(); }
bool encodes(const Reply& r) { return encode(r).ok(); }

Result<Request> request_from(const char* wire) {
  auto frame = decode_serial(hex(wire));
  EXPECT_TRUE(frame.ok()) << wire;
  return decode_request(*frame);
}

Result<Reply> reply_from(const char* wire) {
  auto frame = decode_serial(hex(wire));
  EXPECT_TRUE(frame.ok()) << wire;
  return decode_reply(*frame);
}

std::vector<std::uint8_t> ones(std::size_t n) { return std::vector<std::uint8_t>(n, 1); }

TEST(LscRange, MultiServoMoveExplicitNoMoveValueIsAnError) {
  auto frame = encode(Request{MultiServoMove{100, {{1, kNoMove}}}});
  ASSERT_FALSE(frame.ok());
  EXPECT_NE(frame.error().message.find("0xff00"), std::string::npos) << frame.error().message;
}

TEST(LscRange, MultiServoMoveTooManyServos) {
  MultiServoMove m{100, {}};
  m.servos.resize(84, MultiServoMove::Entry{1, 1500});  // 3 + 3*84 = 255 > 253
  EXPECT_FALSE(encodes(m));
  m.servos.resize(256, MultiServoMove::Entry{1, 1500});  // count does not fit a byte
  EXPECT_FALSE(encodes(m));
}

TEST(LscRange, IdListsMustFitOneFrame) {
  EXPECT_TRUE(encodes(MultiServoOff{ones(252)}));
  EXPECT_FALSE(encodes(MultiServoOff{ones(253)}));
  EXPECT_FALSE(encodes(ServoPositionRead{ones(256)}));
  EXPECT_FALSE(encodes(ServoOffsetWrite{ones(300)}));
  EXPECT_FALSE(encodes(ServoOffsetRead{ones(253)}));
}

TEST(LscRange, ReplyListsMustFitOneFrame) {
  EXPECT_FALSE(encodes(ServoPositions{std::vector<ServoTarget>(85, {1, 1})}));
  EXPECT_FALSE(encodes(ServoOffsets{std::vector<ServoOffsets::Entry>(127, {1, 1})}));
}

TEST(LscRange, ServoSpeedMode) {
  EXPECT_FALSE(encodes(ServoSpeed{1, static_cast<ServoMode>(2), 100}));
  EXPECT_FALSE(request_from("55 55 06 1A 01 02 F4 01").ok());
}

TEST(LscRange, BusServoLeds) {
  BusServoInfoWrite m;
  m.limits.led_status = 2;
  EXPECT_FALSE(encodes(m));
  m.limits.led_status = 1;
  m.limits.led_warning = 8;
  EXPECT_FALSE(encodes(m));
  m.limits.led_warning = 7;
  EXPECT_TRUE(encodes(m));
  EXPECT_FALSE(request_from("55 55 0F 1B 01 00 00 E8 03 94 11 E0 2E 55 00 02 07").ok());
  EXPECT_FALSE(request_from("55 55 0F 1B 01 00 00 E8 03 94 11 E0 2E 55 00 01 08").ok());
  EXPECT_FALSE(
      reply_from("55 55 15 1C 01 00 00 E8 03 94 11 E0 2E 55 00 01 10 FE F4 01 28 E8 1C").ok());
}

TEST(LscRange, GroupDownloadStepFields) {
  EXPECT_FALSE(encodes(GroupDownloadOpen{0, {}}));
  EXPECT_FALSE(encodes(GroupDownloadOpen{0, {255, 255, 255, 255, 1}}));
  EXPECT_FALSE(encodes(GroupDownloadOpen{0, {255, 0}}));
  EXPECT_FALSE(encodes(GroupDownloadSize{0, 4, 1}));
  EXPECT_FALSE(encodes(GroupDownloadSize{0, 0, 0}));
  EXPECT_FALSE(encodes(GroupDownloadBlocks{0, 0}));
  EXPECT_FALSE(encodes(GroupDownloadBlocks{0, 5}));
  EXPECT_FALSE(encodes(GroupDownloadAction{0, 4, 0, 100, {}}));
  EXPECT_FALSE(encodes(GroupDownloadAction{0, 0, 255, 100, {}}));
  GroupDownloadAction wide{0, 0, 0, 100, std::vector<ServoTarget>(83, {1, 1500})};
  EXPECT_FALSE(encodes(wide));  // 7 + 3*83 = 256 data bytes
}

TEST(LscRange, RequestDataLengthMustMatchExactly) {
  EXPECT_FALSE(request_from("55 55 07 03 01 E8 03 01 D0").ok());           // count 1, short
  EXPECT_FALSE(request_from("55 55 0A 03 01 E8 03 01 D0 07 00 00").ok());  // trailing
  EXPECT_FALSE(request_from("55 55 02 03").ok());                          // no count
  EXPECT_FALSE(request_from("55 55 04 06 02 01").ok());                    // GroupRun short
  EXPECT_FALSE(request_from("55 55 06 06 02 01 00 00").ok());              // GroupRun long
  EXPECT_FALSE(request_from("55 55 03 07 00").ok());                       // GroupStop data
  EXPECT_FALSE(request_from("55 55 02 08").ok());                          // GroupErase empty
  EXPECT_FALSE(request_from("55 55 03 0F 00").ok());                       // battery data
  EXPECT_FALSE(request_from("55 55 06 14 04 01 02 03").ok());              // count 4, 3 ids
  EXPECT_FALSE(request_from("55 55 06 15 02 01 02 03").ok());              // count 2, 3 ids
  EXPECT_FALSE(request_from("55 55 03 18 03").ok());                       // no offset
  EXPECT_FALSE(request_from("55 55 03 1C 00").ok());                       // info read data
  EXPECT_FALSE(request_from("55 55 02 99").ok());                          // unknown command
}

TEST(LscRange, GroupDownloadDecodeIsStrict) {
  EXPECT_FALSE(request_from("55 55 04 05 01 00").ok());                 // open, no counts
  EXPECT_FALSE(request_from("55 55 09 05 01 00 FF FF FF FF 01").ok());  // 5 counts
  EXPECT_FALSE(request_from("55 55 05 05 01 00 00").ok());              // count 0
  EXPECT_FALSE(request_from("55 55 07 05 02 00 04 01 00").ok());        // block 4
  EXPECT_FALSE(request_from("55 55 07 05 02 00 00 01 01").ok());        // last byte not 00
  EXPECT_FALSE(request_from("55 55 06 05 02 00 00 01").ok());           // size short
  EXPECT_FALSE(request_from("55 55 06 05 03 00 01 00").ok());           // third byte not 00
  EXPECT_FALSE(request_from("55 55 07 05 03 00 00 01 00").ok());        // list out of order
  EXPECT_FALSE(request_from("55 55 05 05 03 00 00").ok());              // empty list
  EXPECT_FALSE(request_from("55 55 0C 05 04 00 00 00 0C E8 03 01 D0 07").ok());  // marker
  EXPECT_FALSE(request_from("55 55 0B 05 04 00 00 00 0B E8 03 01 D0").ok());     // ragged
  EXPECT_FALSE(request_from("55 55 0C 05 04 00 00 FF 0B E8 03 01 D0 07").ok());  // index 255
  EXPECT_FALSE(request_from("55 55 05 05 05 00 00").ok());                       // close with data
  EXPECT_FALSE(request_from("55 55 04 05 06 00").ok());                          // unknown step
  EXPECT_FALSE(request_from("55 55 03 05 01").ok());                             // no group
}

TEST(LscRange, ReplyDataLengthMustMatchExactly) {
  EXPECT_FALSE(reply_from("55 55 04 07 02 03").ok());                 // GroupStopped 2 bytes
  EXPECT_FALSE(reply_from("55 55 03 08 02").ok());                    // CMD 8 with 1 byte
  EXPECT_FALSE(reply_from("55 55 06 08 02 01 00 00").ok());           // CMD 8 with 4 bytes
  EXPECT_FALSE(reply_from("55 55 02 06").ok());                       // GroupStarted empty
  EXPECT_FALSE(reply_from("55 55 03 0F 4C").ok());                    // battery short
  EXPECT_FALSE(reply_from("55 55 09 15 03 01 F4 01 02 E8 03").ok());  // count 3, 2 entries
  EXPECT_FALSE(reply_from("55 55 07 17 01 01 FD 02 05").ok());        // count 1, 2 entries
  EXPECT_FALSE(reply_from("55 55 03 1C 01").ok());                    // info short
  EXPECT_FALSE(reply_from("55 55 05 05 01 00 00").ok());              // ack 3 bytes
  EXPECT_FALSE(reply_from("55 55 02 03").ok());                       // not a reply
}

TEST(LscRange, CheckedNarrowing) {
  EXPECT_EQ(*checked_u8(0, "servo"), 0);
  EXPECT_EQ(*checked_u8(255, "servo"), 255);
  ASSERT_FALSE(checked_u8(256, "servo").ok());
  EXPECT_EQ(checked_u8(256, "servo").error().message, "servo must be 0..255, got 256");
  EXPECT_EQ(checked_u8(-1, "group").error().message, "group must be 0..255, got -1");
  EXPECT_EQ(*checked_u16(65535, "time_ms"), 65535);
  EXPECT_EQ(checked_u16(65536, "time_ms").error().message, "time_ms must be 0..65535, got 65536");
  EXPECT_EQ(checked_u16(-5, "position").error().message, "position must be 0..65535, got -5");
  EXPECT_EQ(*checked_i16(-32768, "offset"), -32768);
  EXPECT_EQ(*checked_i16(32767, "offset"), 32767);
  EXPECT_EQ(checked_i16(32768, "offset").error().message,
            "offset must be -32768..32767, got 32768");
  EXPECT_EQ(checked_i16(-32769, "offset").error().message,
            "offset must be -32768..32767, got -32769");
}

}  // namespace
}  // namespace seqc::lsc
