// FrameDecoder: chunking, garbage, resynchronisation and impossible LEN values.
#include "protocol/lsc/lsc_stream.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "tests/protocol/wire_test_util.hpp"

namespace seqc::lsc {
namespace {

using test::hex;

std::vector<Frame> drain(FrameDecoder& d) {
  std::vector<Frame> out;
  while (auto f = d.next()) out.push_back(*f);
  return out;
}

std::vector<Frame> decode_all(const Bytes& bytes, std::size_t max_len = 255) {
  FrameDecoder d(max_len);
  d.feed(bytes);
  return drain(d);
}

// Three replies with garbage before and between them.
const char* const kStream =
    "00 FF 55 13 "                       // garbage, including a lone 55
    "55 55 04 0F 4C 1D "                 // battery 7500 mV
    "AA 55 "                             // garbage ending in a 55
    "55 55 09 15 02 01 F4 01 02 E8 03 "  // positions
    "55 55 02 08";                       // group erased
const std::vector<Frame> kExpected = {
    Frame{0x0f, {0x4c, 0x1d}},
    Frame{0x15, {0x02, 0x01, 0xf4, 0x01, 0x02, 0xe8, 0x03}},
    Frame{0x08, {}},
};

TEST(FrameDecoder, GarbageBeforeAndBetweenFrames) {
  EXPECT_EQ(decode_all(hex(kStream)), kExpected);
}

TEST(FrameDecoder, CountsSkippedBytes) {
  FrameDecoder d;
  d.feed(hex(kStream));
  drain(d);
  EXPECT_EQ(d.skipped_bytes(), 6u);  // 00 FF 55 13, then AA 55
  EXPECT_EQ(d.pending_bytes(), 0u);
}

TEST(FrameDecoder, ByteByByte) {
  FrameDecoder d;
  std::vector<Frame> got;
  for (std::uint8_t b : hex(kStream)) {
    d.feed(ByteView(&b, 1));
    auto more = drain(d);
    got.insert(got.end(), more.begin(), more.end());
  }
  EXPECT_EQ(got, kExpected);
}

TEST(FrameDecoder, EverySplitPoint) {
  const Bytes all = hex(kStream);
  for (std::size_t split = 0; split <= all.size(); ++split) {
    FrameDecoder d;
    d.feed(ByteView(all).first(split));
    auto got = drain(d);
    d.feed(ByteView(all).subspan(split));
    auto rest = drain(d);
    got.insert(got.end(), rest.begin(), rest.end());
    EXPECT_EQ(got, kExpected) << "split at " << split;
  }
}

TEST(FrameDecoder, EveryChunkSize) {
  const Bytes all = hex(kStream);
  for (std::size_t chunk = 1; chunk <= all.size(); ++chunk) {
    FrameDecoder d;
    std::vector<Frame> got;
    for (std::size_t at = 0; at < all.size(); at += chunk) {
      d.feed(ByteView(all).subspan(at, std::min(chunk, all.size() - at)));
      auto more = drain(d);
      got.insert(got.end(), more.begin(), more.end());
    }
    EXPECT_EQ(got, kExpected) << "chunk size " << chunk;
  }
}

TEST(FrameDecoder, TruncatedFrameYieldsNothingUntilComplete) {
  const Bytes frame = hex("55 55 09 15 02 01 F4 01 02 E8 03");
  FrameDecoder d;
  for (std::size_t i = 0; i + 1 < frame.size(); ++i) {
    d.feed(ByteView(frame).subspan(i, 1));
    EXPECT_FALSE(d.next().has_value()) << "after " << i + 1 << " bytes";
  }
  EXPECT_EQ(d.pending_bytes(), frame.size() - 1);
  d.feed(ByteView(frame).last(1));
  auto f = d.next();
  ASSERT_TRUE(f.has_value());
  EXPECT_EQ(f->cmd, 0x15);
  EXPECT_EQ(d.pending_bytes(), 0u);
}

TEST(FrameDecoder, LenZeroAndOneAreRejectedAndResynced) {
  EXPECT_EQ(decode_all(hex("55 55 00 55 55 02 0F")), (std::vector<Frame>{Frame{0x0f, {}}}));
  EXPECT_EQ(decode_all(hex("55 55 01 55 55 02 0F")), (std::vector<Frame>{Frame{0x0f, {}}}));
}

TEST(FrameDecoder, LenAboveMaxIsRejectedAndAFrameInsideIsFound) {
  // With max_len 62 (one HID report), LEN 0x40 is impossible; the real frame that starts
  // inside the rejected one is still found.
  const Bytes bytes = hex("55 55 40 07 55 55 04 0F 4C 1D");
  EXPECT_EQ(decode_all(bytes, 62), (std::vector<Frame>{Frame{0x0f, {0x4c, 0x1d}}}));
  // With the default maximum the same LEN is possible, so the decoder waits for 66 bytes.
  FrameDecoder d;
  d.feed(bytes);
  EXPECT_FALSE(d.next().has_value());
  EXPECT_EQ(d.pending_bytes(), bytes.size());
}

TEST(FrameDecoder, HeaderStartsAtSecondOfThree55s) {
  EXPECT_EQ(decode_all(hex("55 55 55 04 0F 4C 1D")),
            (std::vector<Frame>{Frame{0x0f, {0x4c, 0x1d}}}));
  EXPECT_EQ(decode_all(hex("55 55 55 55 02 08")), (std::vector<Frame>{Frame{0x08, {}}}));
  // The same after a complete frame, fed one byte at a time.
  FrameDecoder d;
  std::vector<Frame> got;
  for (std::uint8_t b : hex("55 55 02 07 55 55 55 02 08")) {
    d.feed(ByteView(&b, 1));
    auto more = drain(d);
    got.insert(got.end(), more.begin(), more.end());
  }
  EXPECT_EQ(got, (std::vector<Frame>{Frame{0x07, {}}, Frame{0x08, {}}}));
}

TEST(FrameDecoder, DataBytesEqualTo55DoNotConfuseIt) {
  EXPECT_EQ(decode_all(hex("55 55 05 06 55 55 00 55 55 02 07")),
            (std::vector<Frame>{Frame{0x06, {0x55, 0x55, 0x00}}, Frame{0x07, {}}}));
}

TEST(FrameDecoder, ResetDropsPendingBytes) {
  FrameDecoder d;
  d.feed(hex("55 55 04 0F 4C"));
  EXPECT_FALSE(d.next().has_value());
  d.reset();
  EXPECT_EQ(d.pending_bytes(), 0u);
  d.feed(hex("55 55 02 08"));
  auto f = d.next();
  ASSERT_TRUE(f.has_value());
  EXPECT_EQ(*f, (Frame{0x08, {}}));
}

TEST(FrameDecoder, OnlyGarbageIsAllSkipped) {
  FrameDecoder d;
  d.feed(hex("01 02 03 55 00 55"));
  EXPECT_FALSE(d.next().has_value());
  EXPECT_EQ(d.skipped_bytes(), 5u);
  EXPECT_EQ(d.pending_bytes(), 1u);  // the last 55 may start a header
}

}  // namespace
}  // namespace seqc::lsc
