// Raspblock packets: golden vectors written by hand from docs/protocol/raspblock.md
// (big-endian, CHK = (FUNC + LEN + sum(DATA)) & 0xFF), round
// trips, range checks and the stream decoder.
#include "protocol/raspblock/raspblock.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "tests/protocol/wire_test_util.hpp"

namespace seqc::raspblock {
namespace {

using test::hex;
using test::hex_or_error;
using test::norm;

struct Vector {
  const char* name;
  Packet value;
  const char* wire;
};

std::vector<Vector> vectors() {
  return {
      // The vendor driver's example.
      {"rocker x=-10", Rocker{-10, 0, 0}, "FF FE 03 08 01 00 0A 00 00 00 00 05 1B"},
      // Y bit for y < 0; Z bit clear for z < 0. CHK = 3+8+1+25+25+200+2 = 264 -> 08.
      {"rocker extremes", Rocker{25, -25, -200}, "FF FE 03 08 01 00 19 00 19 00 C8 02 08"},
      // Z bit set for z >= 0. CHK = 3+8+1+200+1 = 213 = D5.
      {"rocker z=200", Rocker{0, 0, 200}, "FF FE 03 08 01 00 00 00 00 00 C8 01 D5"},
      // 1500 = 05 DC, 1950 = 07 9E. CHK = 2+4+5+220+7+158 = 396 -> 8C.
      {"gimbal", GimbalServos{1500, 1950}, "FF FE 02 04 05 DC 07 9E 8C"},
      // 2500 = 09 C4. CHK = 2+3+2+9+196 = 212 = D4.
      {"single servo", SingleServo{2, 2500}, "FF FE 02 03 02 09 C4 D4"},
      // CHK = 1+9+1+(1+...+8) = 47 = 2F.
      {"pid", PidAdjust{PidMode::Position, 1, 2, 3, 4, 5, 6, 7, 8},
       "FF FE 01 09 01 01 02 03 04 05 06 07 08 2F"},
  };
}

TEST(RaspblockGolden, Encode) {
  for (const auto& v : vectors()) EXPECT_EQ(hex_or_error(encode(v.value)), norm(v.wire)) << v.name;
}

TEST(RaspblockGolden, Decode) {
  for (const auto& v : vectors()) {
    auto p = decode(hex(v.wire));
    ASSERT_TRUE(p.ok()) << v.name << ": " << p.error().message;
    EXPECT_EQ(*p, v.value) << v.name;
  }
}

TEST(RaspblockRoundTrip, AtEdges) {
  const std::vector<Packet> packets = {
      PidAdjust{},
      PidAdjust{PidMode::Position, 255, 255, 255, 255, 255, 255, 255, 255},
      GimbalServos{500, 500},
      GimbalServos{2500, 1950},
      SingleServo{1, 500},
      SingleServo{4, 2500},
      Rocker{0, 0, 0},
      Rocker{-25, -25, -200},
      Rocker{25, 25, 200},
      Rocker{-1, 1, -1},
  };
  for (const Packet& p : packets) {
    auto bytes = encode(p);
    ASSERT_TRUE(bytes.ok()) << describe(p) << ": " << bytes.error().message;
    auto back = decode(*bytes);
    ASSERT_TRUE(back.ok()) << describe(p) << ": " << back.error().message;
    EXPECT_EQ(*back, p) << describe(p);
  }
}

TEST(RaspblockRange, EncodeRejectsOutOfRange) {
  EXPECT_FALSE(encode(GimbalServos{499, 1500}).ok());
  EXPECT_FALSE(encode(GimbalServos{2501, 1500}).ok());
  EXPECT_FALSE(encode(GimbalServos{1500, 499}).ok());
  EXPECT_FALSE(encode(GimbalServos{1500, 1951}).ok());
  EXPECT_FALSE(encode(SingleServo{0, 1500}).ok());
  EXPECT_FALSE(encode(SingleServo{5, 1500}).ok());
  EXPECT_FALSE(encode(SingleServo{1, 2501}).ok());
  EXPECT_FALSE(encode(SingleServo{1, 499}).ok());
  EXPECT_FALSE(encode(PidAdjust{static_cast<PidMode>(2)}).ok());
  EXPECT_FALSE(encode(Rocker{26, 0, 0}).ok());
  EXPECT_FALSE(encode(Rocker{-26, 0, 0}).ok());
  EXPECT_FALSE(encode(Rocker{0, 26, 0}).ok());
  EXPECT_FALSE(encode(Rocker{0, -26, 0}).ok());
  EXPECT_FALSE(encode(Rocker{0, 0, 201}).ok());
  EXPECT_FALSE(encode(Rocker{0, 0, -201}).ok());
  EXPECT_EQ(encode(GimbalServos{1500, 1951}).error().message,
            "GimbalServos vertical 1951 is outside 500..1950");
}

TEST(RaspblockDecode, Rejects) {
  // Each is a golden packet with one thing wrong (checksums recomputed by hand where needed).
  EXPECT_FALSE(decode(hex("FF FE 03 08 01 00 0A 00 00 00 00 05 1C")).ok());     // checksum
  EXPECT_FALSE(decode(hex("FF FE 03 08 02 00 0A 00 00 00 00 05 1C")).ok());     // mode 2
  EXPECT_FALSE(decode(hex("FF FE 03 08 01 00 1A 00 00 00 00 05 2B")).ok());     // |x| = 26
  EXPECT_FALSE(decode(hex("FF FE 03 08 01 00 00 00 00 00 C9 01 D6")).ok());     // |z| = 201
  EXPECT_FALSE(decode(hex("FF FE 03 08 01 00 00 00 00 00 00 09 15")).ok());     // bit 3
  EXPECT_FALSE(decode(hex("FF FE 03 08 01 00 00 00 00 00 00 05 11")).ok());     // x = -0
  EXPECT_FALSE(decode(hex("FF FE 03 08 01 00 00 00 00 00 00 00 0C")).ok());     // z = -0
  EXPECT_FALSE(decode(hex("FF FE 02 04 01 F3 07 9E 9F")).ok());                 // horizontal 499
  EXPECT_FALSE(decode(hex("FF FE 02 04 05 DC 07 9F 8D")).ok());                 // vertical 1951
  EXPECT_FALSE(decode(hex("FF FE 02 03 05 09 C4 D7")).ok());                    // index 5
  EXPECT_FALSE(decode(hex("FF FE 02 03 00 05 DC E6")).ok());                    // index 0
  EXPECT_FALSE(decode(hex("FF FE 02 05 05 DC 07 9E 00 8D")).ok());              // servo LEN 5
  EXPECT_FALSE(decode(hex("FF FE 01 08 01 01 02 03 04 05 06 07 26")).ok());     // pid LEN 8
  EXPECT_FALSE(decode(hex("FF FE 01 09 02 01 02 03 04 05 06 07 08 30")).ok());  // pid mode 2
  EXPECT_FALSE(decode(hex("FF FE 04 01 00 05")).ok());                          // unknown function
  EXPECT_FALSE(decode(hex("FF FD 02 03 02 09 C4 D4")).ok());                    // header
  EXPECT_FALSE(decode(hex("FF FE 02 03 02 09 C4")).ok());                       // truncated
  EXPECT_FALSE(decode(hex("FF FE 02 03 02 09 C4 D4 00")).ok());                 // trailing
}

std::vector<Result<Packet>> drain(PacketDecoder& d) {
  std::vector<Result<Packet>> out;
  while (auto r = d.next()) out.push_back(*r);
  return out;
}

// Garbage, a gimbal packet, a packet with a bad checksum, garbage, a rocker packet.
const char* const kStream =
    "00 FF 12 "
    "FF FE 02 04 05 DC 07 9E 8C "
    "FF FE 02 03 02 09 C4 00 "
    "FE FF "
    "FF FE 03 08 01 00 0A 00 00 00 00 05 1B";

void expect_stream_result(const std::vector<Result<Packet>>& got) {
  ASSERT_EQ(got.size(), 3u);
  ASSERT_TRUE(got[0].ok());
  EXPECT_EQ(*got[0], (Packet{GimbalServos{1500, 1950}}));
  ASSERT_FALSE(got[1].ok());
  EXPECT_NE(got[1].error().message.find("checksum"), std::string::npos) << got[1].error().message;
  ASSERT_TRUE(got[2].ok());
  EXPECT_EQ(*got[2], (Packet{Rocker{-10, 0, 0}}));
}

TEST(RaspblockStream, BadChecksumIsReportedAndDecodingResyncs) {
  PacketDecoder d;
  d.feed(hex(kStream));
  expect_stream_result(drain(d));
}

TEST(RaspblockStream, EverySplitPoint) {
  const Bytes all = hex(kStream);
  for (std::size_t split = 0; split <= all.size(); ++split) {
    PacketDecoder d;
    d.feed(ByteView(all).first(split));
    auto got = drain(d);
    d.feed(ByteView(all).subspan(split));
    auto rest = drain(d);
    got.insert(got.end(), rest.begin(), rest.end());
    SCOPED_TRACE("split at " + std::to_string(split));
    expect_stream_result(got);
  }
}

TEST(RaspblockStream, ByteByByte) {
  PacketDecoder d;
  std::vector<Result<Packet>> got;
  for (std::uint8_t b : hex(kStream)) {
    d.feed(ByteView(&b, 1));
    auto more = drain(d);
    got.insert(got.end(), more.begin(), more.end());
  }
  expect_stream_result(got);
}

TEST(RaspblockStream, ImpossibleLengthIsReportedAndAPacketInsideIsFound) {
  PacketDecoder d;
  d.feed(hex("FF FE 02 07 FF FE 02 03 02 09 C4 D4"));
  auto got = drain(d);
  ASSERT_EQ(got.size(), 2u);
  EXPECT_FALSE(got[0].ok());
  ASSERT_TRUE(got[1].ok());
  EXPECT_EQ(*got[1], (Packet{SingleServo{2, 2500}}));
}

TEST(RaspblockStream, OutOfRangePacketWithGoodChecksumIsDroppedWhole) {
  PacketDecoder d;
  d.feed(hex("FF FE 02 03 05 09 C4 D7 FF FE 02 03 02 09 C4 D4"));
  auto got = drain(d);
  ASSERT_EQ(got.size(), 2u);
  EXPECT_FALSE(got[0].ok());
  ASSERT_TRUE(got[1].ok());
  EXPECT_EQ(d.skipped_bytes(), 8u);
}

TEST(RaspblockStream, TruncatedPacketWaits) {
  PacketDecoder d;
  d.feed(hex("FF FE 02 03 02 09 C4"));
  EXPECT_FALSE(d.next().has_value());
  d.feed(hex("D4"));
  auto r = d.next();
  ASSERT_TRUE(r.has_value());
  ASSERT_TRUE(r->ok());
}

TEST(RaspblockDescribe, Lines) {
  EXPECT_EQ(describe(Rocker{-10, 0, 200}), "Rocker x=-10 y=0 z=200");
  EXPECT_EQ(describe(GimbalServos{1500, 1950}), "GimbalServos horizontal=1500 vertical=1950");
  EXPECT_EQ(describe(SingleServo{2, 2500}), "SingleServo index=2 position=2500");
  EXPECT_EQ(describe(PidAdjust{PidMode::Position, 1, 2, 3, 4, 5, 6, 7, 8}),
            "PidAdjust mode=position speed_kp=1 speed_ki=2 position_kp=3 position_ki=4 "
            "position_kd=5 yaw_kp=6 yaw_ki=7 yaw_kd=8");
}

}  // namespace
}  // namespace seqc::raspblock
