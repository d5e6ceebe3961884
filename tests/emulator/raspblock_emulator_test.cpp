// The Raspblock board emulator: timeline of state changes and checksum rejection.
#include <gtest/gtest.h>

#include "runtime/emulator/raspblock_emulator.hpp"
#include "tests/emulator/emu_test_util.hpp"

namespace seqc::emu::test {
namespace {

using F = RaspblockField;

RaspblockChange change(std::int64_t ms, F field, std::optional<int> previous, int value) {
  return RaspblockChange{at_ms(ms), field, previous, value};
}

TEST(RaspblockEmulator, TimelineOfStateChanges) {
  RaspblockEmulator board;
  board.receive(hex("ff fe 02 04 05 dc 03 e8 d2"), at_ms(0));                  // gimbal 1500, 1000
  board.receive(hex("ff fe 02 03 03 07 d0 df"), at_ms(10));                    // servo 3 to 2000
  board.receive(hex("ff fe 03 08 01 00 0a 00 00 00 00 05 1b"), at_ms(20));     // X=-10 (vendor)
  board.receive(hex("ff fe 01 09 01 0a 0b 0c 0d 0e 0f 10 11 77"), at_ms(30));  // PID
  board.receive(hex("ff fe 02 04 05 dc 03 e8 d2"), at_ms(50));  // same gimbal: no change
  board.receive(hex("ff fe 02 04 06 40"), at_ms(59));           // split packet...
  board.receive(hex("03 e8 37"), at_ms(60));                    // ...completes at 60 ms

  const std::vector<RaspblockChange> want = {
      change(0, F::GimbalHorizontal, std::nullopt, 1500),
      change(0, F::GimbalVertical, std::nullopt, 1000),
      change(10, F::Servo3, std::nullopt, 2000),
      change(20, F::RockerX, std::nullopt, -10),
      change(20, F::RockerY, std::nullopt, 0),
      change(20, F::RockerZ, std::nullopt, 0),
      change(30, F::PidMode, std::nullopt, 1),
      change(30, F::SpeedKp, std::nullopt, 10),
      change(30, F::SpeedKi, std::nullopt, 11),
      change(30, F::PositionKp, std::nullopt, 12),
      change(30, F::PositionKi, std::nullopt, 13),
      change(30, F::PositionKd, std::nullopt, 14),
      change(30, F::YawKp, std::nullopt, 15),
      change(30, F::YawKi, std::nullopt, 16),
      change(30, F::YawKd, std::nullopt, 17),
      change(60, F::GimbalHorizontal, 1500, 1600),
  };
  EXPECT_EQ(board.timeline(), want);
  EXPECT_EQ(board.packets().size(), 6u);
  EXPECT_EQ(board.packets().back().at, at_ms(60));
  EXPECT_EQ(board.value(F::GimbalHorizontal), 1600);
  EXPECT_EQ(board.value(F::Servo1), std::nullopt);
  EXPECT_EQ(board.chunks().size(), 7u);
  EXPECT_EQ(board.received_bytes().size(), 9u + 8 + 13 + 14 + 9 + 9);

  EXPECT_EQ(describe_change(board.timeline().back()),
            "    0.060000 s  gimbal.horizontal 1500 -> 1600");
  EXPECT_EQ(describe_change(board.timeline()[2]), "    0.010000 s  servo.3 = 2000");
  const std::string csv = timeline_csv(board.timeline());
  EXPECT_EQ(csv.substr(0, csv.find('\n', csv.find('\n') + 1) + 1),
            "time_s,field,previous,value\n0.000000,gimbal.horizontal,,1500\n");
  EXPECT_NE(csv.find("\n0.020000,rocker.x,,-10\n"), std::string::npos);
  EXPECT_TRUE(csv.ends_with("0.060000,gimbal.horizontal,1500,1600\n"));
}

TEST(RaspblockEmulator, BadChecksumRejectedAndCounted) {
  RaspblockEmulator board;
  board.receive(hex("ff fe 02 04 05 dc 03 e8 d3"), at_ms(5));  // checksum should be d2
  EXPECT_EQ(board.bad_checksums(), 1u);
  ASSERT_EQ(board.rejections().size(), 1u);
  EXPECT_EQ(board.rejections()[0].at, at_ms(5));
  EXPECT_TRUE(board.timeline().empty());
  EXPECT_TRUE(board.packets().empty());
  // The board resynchronises: the next good packet is taken.
  board.receive(hex("00 ff fe 02 03 03 07 d0 df"), at_ms(6));
  ASSERT_EQ(board.timeline().size(), 1u);
  EXPECT_EQ(board.timeline()[0], change(6, F::Servo3, std::nullopt, 2000));
  EXPECT_EQ(board.bad_checksums(), 1u);
}

// The header, function and length rules after a packet was taken, and a half-received packet
// followed by a whole one (docs/protocol/raspblock.md).
TEST(RaspblockEmulator, RejectionsAfterTrafficLeaveTheStateAlone) {
  RaspblockEmulator board;
  board.receive(hex("ff fe 02 03 03 07 d0 df"), at_ms(0));         // servo 3 to 2000
  board.receive(hex("ff fe 09 01 00 0a"), at_ms(10));              // function 9: none such
  board.receive(hex("ff fe 02 05 01 05 dc 00 00 e9"), at_ms(20));  // function 2 has LEN 3 or 4
  board.receive(hex("ff fd 02 03 01 05 dc e7"), at_ms(30));        // bad second header byte
  // Half of a servo 3 packet, then a whole servo 1 packet: the half takes the next two bytes
  // as its data and checksum and fails; the whole one is found after it.
  board.receive(hex("ff fe 02 03 03 07"), at_ms(35));
  board.receive(hex("ff fe 02 03 01 05 dc e7"), at_ms(40));  // servo 1 to 1500
  board.receive(hex("ff fe 02 03 03 05 dc e9"), at_ms(50));  // servo 3 to 1500

  const std::vector<RaspblockChange> want = {
      change(0, F::Servo3, std::nullopt, 2000),
      change(40, F::Servo1, std::nullopt, 1500),
      change(50, F::Servo3, 2000, 1500),
  };
  EXPECT_EQ(board.timeline(), want);
  ASSERT_EQ(board.rejections().size(), 3u);
  EXPECT_EQ(board.rejections()[0].reason, "Raspblock packet rejected: unknown function 9");
  EXPECT_EQ(board.rejections()[0].at, at_ms(10));
  EXPECT_EQ(board.rejections()[1].reason,
            "Raspblock packet rejected: function 2 cannot have LEN 5");
  EXPECT_EQ(board.rejections()[2].reason, "Raspblock packet: checksum fe, expected 0e");
  EXPECT_EQ(board.rejections()[2].at, at_ms(40));
  EXPECT_EQ(board.bad_checksums(), 1u);
  EXPECT_EQ(board.packets().size(), 3u);
}

}  // namespace
}  // namespace seqc::emu::test
