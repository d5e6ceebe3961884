// Forms public client libraries send to the xArm controller beyond the command table, as
// docs/protocol/readings.md reads them: ServoOffsetAdjust with a one-byte offset,
// BusServoInfoWrite with only an id, and the bus broadcast id 254. Bytes written by hand.
#include <gtest/gtest.h>

#include "protocol/lsc/lsc_frame.hpp"
#include "tests/emulator/emu_test_util.hpp"

namespace seqc::emu::test {
namespace {

TEST(XArmShortForms, ServoOffsetAdjustWithAOneByteOffset) {
  XArmEmulator emu;
  io::TimePoint t = at_ms(0);
  // id 3, offset 0xec (-20); id 2, offset 0x1e (+30). No answer to either.
  EXPECT_EQ(hex_of(exchange(emu, hex("55 55 04 18 03 ec"), t)), "");
  EXPECT_EQ(hex_of(exchange(emu, hex("55 55 04 18 02 1e"), t)), "");
  EXPECT_EQ(hex_of(exchange(emu, hex("55 55 05 17 02 03 02"), t)), "55 55 07 17 02 03 ec 02 1e");
  // The table's two-byte form still works after it: id 3, 0xfff6 (-10).
  EXPECT_EQ(hex_of(exchange(emu, hex("55 55 05 18 03 f6 ff"), t)), "");
  EXPECT_EQ(hex_of(exchange(emu, hex("55 55 04 17 01 03"), t)), "55 55 05 17 01 03 f6");
}

TEST(XArmShortForms, TheOneByteOffsetDecodesAndDescribes) {
  auto frame = lsc::decode_serial(hex("55 55 04 18 03 ec"));
  ASSERT_TRUE(frame.ok());
  auto request = lsc::decode_request(*frame);
  ASSERT_TRUE(request.ok()) << request.error().message;
  EXPECT_EQ(lsc::describe(*request), "ServoOffsetAdjust servo=3 offset=-20 (one-byte form)");
  auto again = lsc::encode(*request);
  ASSERT_TRUE(again.ok());
  EXPECT_EQ(hex_of(*lsc::encode_serial(*again)), "55 55 04 18 03 ec") << "the same form back";
  EXPECT_FALSE(lsc::decode_request(*lsc::decode_serial(hex("55 55 03 18 03"))).ok())
      << "an id without an offset";
}

TEST(XArmShortForms, BusServoInfoWriteWithOnlyAnIdRenumbersTheServo) {
  XArmConfig one;
  one.servo_count = 1;  // one servo attached, as a library renumbering a servo requires
  XArmEmulator emu(one);
  io::TimePoint t = at_ms(0);
  EXPECT_EQ(hex_of(exchange(emu, hex("55 55 03 1b 05"), t)), "") << "no answer";
  EXPECT_EQ(hex_of(exchange(emu, hex("55 55 05 15 02 01 05"), t)), "55 55 06 15 01 05 f4 01")
      << "only id 5 answers now";
  // Servo 5 to 800 (20 03) in 1000 ms (e8 03).
  EXPECT_EQ(hex_of(exchange(emu, hex("55 55 08 03 01 e8 03 05 20 03"), t)), "");
  t += 1s;
  EXPECT_EQ(hex_of(exchange(emu, hex("55 55 02 1c"), t)),
            "55 55 15 1c 05 00 00 e8 03 00 00 00 00 00 00 00 00 00 20 03 20 4c 1d");
  // 254 is the broadcast id, not a servo's: ignored.
  EXPECT_EQ(hex_of(exchange(emu, hex("55 55 03 1b fe"), t)), "");
  EXPECT_EQ(hex_of(exchange(emu, hex("55 55 04 15 01 05"), t)), "55 55 06 15 01 05 20 03");
  // The id is the servo's own: it survives a power cycle.
  emu.power_cycle(t);
  EXPECT_EQ(hex_of(exchange(emu, hex("55 55 04 15 01 05"), t)), "55 55 06 15 01 05 20 03");
}

TEST(XArmShortForms, AnIdOnlyWriteReachesEveryServoOnTheBus) {
  XArmEmulator emu;  // six servos, ids 1-6
  io::TimePoint t = at_ms(0);
  EXPECT_EQ(hex_of(exchange(emu, hex("55 55 03 1b 09"), t)), "");
  EXPECT_EQ(hex_of(exchange(emu, hex("55 55 05 15 02 01 06"), t)), "55 55 03 15 00");
  EXPECT_EQ(hex_of(exchange(emu, hex("55 55 04 15 01 09"), t)), "55 55 06 15 01 09 f4 01");
  EXPECT_EQ(emu.servos().ids(), (std::vector<std::uint8_t>{9, 9, 9, 9, 9, 9}));
}

TEST(XArmShortForms, TheBroadcastIdReachesEveryServo) {
  XArmEmulator emu;
  io::TimePoint t = at_ms(0);
  // MultiServoMove: 254 to 800 in 1000 ms.
  EXPECT_EQ(hex_of(exchange(emu, hex("55 55 08 03 01 e8 03 fe 20 03"), t)), "");
  t += 1s;
  EXPECT_EQ(hex_of(exchange(emu, hex("55 55 0a 15 07 01 02 03 04 05 06 fe"), t)),
            "55 55 15 15 06 01 20 03 02 20 03 03 20 03 04 20 03 05 20 03 06 20 03")
      << "every servo moved; nothing answers for 254 itself";
  // ServoOffsetAdjust (one-byte form) and ServoOffsetWrite to 254.
  EXPECT_EQ(hex_of(exchange(emu, hex("55 55 04 18 fe 0a"), t)), "");
  EXPECT_EQ(hex_of(exchange(emu, hex("55 55 04 16 01 fe"), t)), "");
  EXPECT_EQ(hex_of(exchange(emu, hex("55 55 05 17 02 01 06"), t)), "55 55 07 17 02 01 0a 06 0a");
  EXPECT_EQ(emu.servos().stored_offset(4), 10);
  // ServoSpeed to 254: motor mode, 500 ms.
  EXPECT_EQ(hex_of(exchange(emu, hex("55 55 06 1a fe 01 f4 01"), t)), "");
  EXPECT_EQ(emu.servos().mode(2), lsc::ServoMode::Motor);
  EXPECT_EQ(emu.servos().mode_milliseconds(6), 500);
  // MultiServoOff to 254: all go limp.
  EXPECT_EQ(hex_of(exchange(emu, hex("55 55 04 14 01 fe"), t)), "");
  for (std::uint8_t id = 1; id <= 6; ++id) EXPECT_FALSE(emu.servos().powered(id)) << int{id};
}

}  // namespace
}  // namespace seqc::emu::test
