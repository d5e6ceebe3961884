// Serial and HID framing of the servo controller (docs/protocol/servo-controller.md, "Framing").
#include "protocol/lsc/lsc_frame.hpp"

#include <gtest/gtest.h>

#include "tests/protocol/wire_test_util.hpp"

namespace seqc::lsc {
namespace {

using test::hex;
using test::hex_or_error;
using test::norm;

TEST(LscFrame, SerialEncodeVendorMoveExample) {
  const Frame frame{0x03, hex("01 E8 03 01 D0 07")};
  EXPECT_EQ(hex_or_error(encode_serial(frame)), norm("55 55 08 03 01 E8 03 01 D0 07"));
}

TEST(LscFrame, SerialEncodeNoData) {
  EXPECT_EQ(hex_or_error(encode_serial(Frame{0x0f, {}})), norm("55 55 02 0F"));
}

TEST(LscFrame, SerialDecode) {
  auto frame = decode_serial(hex("55 55 04 0F 4C 1D"));
  ASSERT_TRUE(frame.ok()) << frame.error().message;
  EXPECT_EQ(frame->cmd, 0x0f);
  EXPECT_EQ(frame->data, hex("4C 1D"));
}

TEST(LscFrame, SerialLargestFrameFitsAndOneMoreDoesNot) {
  Frame frame{0x14, Bytes(253, 0x01)};
  auto bytes = encode_serial(frame);
  ASSERT_TRUE(bytes.ok());
  ASSERT_EQ(bytes->size(), 257u);
  EXPECT_EQ((*bytes)[2], 0xff);
  auto back = decode_serial(*bytes);
  ASSERT_TRUE(back.ok());
  EXPECT_EQ(*back, frame);

  frame.data.push_back(0x01);
  EXPECT_FALSE(encode_serial(frame).ok());
}

TEST(LscFrame, SerialDecodeRejectsMalformed) {
  EXPECT_FALSE(decode_serial(hex("")).ok());
  EXPECT_FALSE(decode_serial(hex("55 55 02")).ok());     // no CMD
  EXPECT_FALSE(decode_serial(hex("55 54 02 0F")).ok());  // bad header
  EXPECT_FALSE(decode_serial(hex("55 55 01 0F")).ok());  // LEN below 2
  EXPECT_FALSE(decode_serial(hex("55 55 00 0F")).ok());
  EXPECT_FALSE(decode_serial(hex("55 55 04 0F 4C")).ok());        // missing a byte
  EXPECT_FALSE(decode_serial(hex("55 55 04 0F 4C 1D 00")).ok());  // trailing byte
}

TEST(LscFrame, HidReportIsReportIdFrameAndZeroPadding) {
  auto report = encode_hid_report(Frame{0x0f, {}});
  ASSERT_TRUE(report.ok());
  Bytes expected = hex("00 55 55 02 0F");
  expected.resize(65, 0x00);
  EXPECT_EQ(to_hex(*report), to_hex(expected));
}

TEST(LscFrame, HidReportLargestFrame) {
  // 64 report bytes = 4 header bytes + 60 data bytes; LEN = 62 = 0x3E.
  const Frame frame{0x14, Bytes(60, 0x07)};
  auto report = encode_hid_report(frame);
  ASSERT_TRUE(report.ok()) << report.error().message;
  ASSERT_EQ(report->size(), 65u);
  EXPECT_EQ(to_hex(ByteView(*report).first(5)), norm("00 55 55 3E 14"));
  EXPECT_EQ((*report)[64], 0x07);

  EXPECT_FALSE(encode_hid_report(Frame{0x14, Bytes(61, 0x07)}).ok());
}

TEST(LscFrame, HidInputReportDecodeIgnoresPadding) {
  Bytes report = hex("55 55 04 0F 4C 1D");
  report.resize(64, 0x00);
  auto frame = decode_hid_report(report);
  ASSERT_TRUE(frame.ok()) << frame.error().message;
  EXPECT_EQ(frame->cmd, 0x0f);
  EXPECT_EQ(frame->data, hex("4C 1D"));
}

TEST(LscFrame, HidInputReportRejectsMalformed) {
  Bytes no_header(64, 0x00);
  EXPECT_FALSE(decode_hid_report(no_header).ok());
  Bytes too_long = hex("55 55 3F 14");  // LEN 63 needs 65 bytes: does not fit in 64
  too_long.resize(64, 0x01);
  EXPECT_FALSE(decode_hid_report(too_long).ok());
  Bytes oversized = hex("55 55 02 0F");
  oversized.resize(65, 0x00);
  EXPECT_FALSE(decode_hid_report(oversized).ok());
  Bytes bad_len = hex("55 55 01 0F");
  bad_len.resize(64, 0x00);
  EXPECT_FALSE(decode_hid_report(bad_len).ok());
}

}  // namespace
}  // namespace seqc::lsc
