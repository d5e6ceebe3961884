// The LSC-6 receiver's length, header and unknown-command rules (docs/protocol/lsc-6.md,
// "Receiver") exercised after other traffic: a completed command, a download in progress, a
// playing group, a half-received frame and a command still in the one-frame buffer. The board's
// command buffer keeps the last frame's bytes, so a rule that holds on a fresh board can still
// fail once that buffer has something in it to replay. Request bytes are written by hand.
#include <gtest/gtest.h>

#include "tests/emulator/lsc6_test_util.hpp"

namespace seqc::emu::test {
namespace {

TEST(Lsc6ReceiverStates, ALenOfOneAfterAMoveIsAbandonedNotReplayed) {
  Lsc6Emulator emu(unpaced());
  // Move: 1 channel, 1000 ms, channel 1 to 2000 us.
  emu.receive(hex("55 55 08 03 01 e8 03 01 d0 07"), at_ms(0));
  emu.advance_to(at_ms(500));
  ASSERT_EQ(emu.pulse(1, at_ms(500)), 1750);
  // The Move's own bytes with its LEN hit to 1: the receiver abandons the frame at the LEN and
  // the rest is noise between frames. The buffer still holds the Move; it must not run again
  // (it would restart from 1750 and be at 1875 at 1000 ms).
  emu.receive(hex("55 55 01 03 01 e8 03 01 d0 07"), at_ms(500));
  emu.advance_to(at_ms(2000));
  EXPECT_EQ(emu.pulse(1, at_ms(750)), 1875);
  EXPECT_EQ(emu.pulse(1, at_ms(1000)), 2000);
  EXPECT_EQ(emu.received().size(), 1u) << "an abandoned frame is never completed";
  EXPECT_EQ(hex_of(emu.take_output(at_ms(2000))), "");
}

TEST(Lsc6ReceiverStates, ALenOfOneAfterARunAnswersNothing) {
  Lsc6Emulator emu(unpaced());
  io::TimePoint t = at_ms(0);
  ASSERT_EQ(hex_of(exchange(emu, download_action(0, 1, 0, 100, 1, 900), t)), "55 55 02 19");
  // Run group 0 once: the answer, then the end of the 100 ms run.
  EXPECT_EQ(hex_of(exchange(emu, hex("55 55 05 06 00 01 00"), t)), "55 55 02 06 55 55 02 07");
  EXPECT_EQ(hex_of(exchange(emu, hex("55 55 01 06 00 01 00"), t, 5s)), "")
      << "no answer and no second run";
  EXPECT_EQ(emu.received().size(), 2u);
  EXPECT_EQ(hex_of(exchange(emu, hex("55 55 02 08"), t)), "55 55 02 08") << "still listening";
}

TEST(Lsc6ReceiverStates, ALenOfOneWhileAGroupPlaysLeavesItPlaying) {
  Lsc6Emulator emu(unpaced());
  io::TimePoint t = at_ms(0);
  ASSERT_EQ(hex_of(exchange(emu, download_action(0, 1, 0, 1000, 1, 900), t)), "55 55 02 19");
  EXPECT_EQ(hex_of(exchange(emu, hex("55 55 05 06 00 00 00"), t)), "55 55 02 06")
      << "group 0 until stopped";
  t += 300ms;
  EXPECT_EQ(hex_of(exchange(emu, hex("55 55 01"), t)), "");
  EXPECT_EQ(hex_of(exchange(emu, hex("55 55 00 07"), t)), "") << "LEN 0: not a Stop";
  EXPECT_EQ(hex_of(exchange(emu, hex("55 55 02 0f"), t)), "") << "no battery command";
  emu.advance_to(t + 5s);
  EXPECT_EQ(emu.playing_group(), 0);
  EXPECT_EQ(hex_of(emu.take_output(t + 5s)), "");
}

TEST(Lsc6ReceiverStates, ALenOfOneMidDownloadNeitherAnswersNorErasesAgain) {
  Lsc6Emulator emu(unpaced());
  io::TimePoint t = at_ms(0);
  ASSERT_EQ(hex_of(exchange(emu, download_action(3, 2, 0, 400, 2, 1200), t)), "55 55 02 19");
  // Replaying index 0 would answer once more and erase the group again (181 ms).
  EXPECT_EQ(hex_of(exchange(emu, hex("55 55 01 19 03 02 01"), t)), "");
  EXPECT_EQ(hex_of(exchange(emu, download_action(3, 2, 1, 600, 5, 1800), t)), "55 55 02 19");
  EXPECT_EQ(emu.stored_count(3), 2);
  const auto stored = emu.stored_group(3);
  ASSERT_TRUE(stored.has_value());
  ASSERT_EQ(stored->size(), 2u);
  EXPECT_EQ((*stored)[0].time_ms, 400);
  EXPECT_EQ((*stored)[0].servos, (std::vector<lsc6::Target>{{2, 1200}}));
  EXPECT_EQ((*stored)[1].servos, (std::vector<lsc6::Target>{{5, 1800}}));
}

TEST(Lsc6ReceiverStates, ALenOfOneBehindABufferedCommandIsNotAFrame) {
  Lsc6Emulator emu(unpaced());
  // Index 0 keeps the board busy erasing (about 181 ms); index 1 waits in the buffer; then a
  // LEN 1 frame: abandoned by the receiver, so it is neither dropped as "buffer full" nor run.
  emu.receive(download_action(4, 2, 0, 100, 1, 1000), at_ms(0));
  emu.receive(download_action(4, 2, 1, 100, 1, 2000), at_ms(10));
  emu.receive(hex("55 55 01"), at_ms(20));
  EXPECT_EQ(hex_of(emu.take_output(at_ms(1000))), "55 55 02 19 55 55 02 19");
  ASSERT_EQ(emu.received().size(), 2u);
  EXPECT_FALSE(emu.received()[1].dropped_busy);
  EXPECT_EQ(emu.stored_count(4), 2);
}

TEST(Lsc6ReceiverStates, HeaderRulesAfterACompletedCommand) {
  Lsc6Emulator emu(unpaced());
  io::TimePoint t = at_ms(0);
  ASSERT_EQ(hex_of(exchange(emu, hex("55 55 02 08"), t)), "55 55 02 08");
  EXPECT_EQ(hex_of(exchange(emu, hex("55 54 02 08"), t)), "") << "a bad second header byte";
  EXPECT_EQ(hex_of(exchange(emu, hex("55 54 55 55 02 08"), t)), "55 55 02 08")
      << "the bad byte resets the count; the next 55 55 starts a frame";
  // A third 55 is not skipped: it is the LEN (0x55), and the frame runs 87 bytes.
  EXPECT_EQ(hex_of(exchange(emu, hex("55 55 55 02 08"), t)), "");
  EXPECT_EQ(hex_of(exchange(emu, hex("55 55 02 08"), t)), "") << "swallowed by that frame";
  // 9 bytes so far; 78 more complete it (its CMD, 02, is no command: ignored).
  EXPECT_EQ(hex_of(exchange(emu, Bytes(78, 0x00), t)), "");
  EXPECT_EQ(hex_of(exchange(emu, hex("55 55 02 08"), t)), "55 55 02 08");
}

TEST(Lsc6ReceiverStates, UnknownCommandsDuringADownloadAreIgnored) {
  Lsc6Emulator emu(unpaced());
  io::TimePoint t = at_ms(0);
  ASSERT_EQ(hex_of(exchange(emu, download_action(1, 2, 0, 300, 3, 1100), t)), "55 55 02 19");
  EXPECT_EQ(hex_of(exchange(emu, hex("55 55 02 0f"), t)), "") << "battery";
  EXPECT_EQ(hex_of(exchange(emu, hex("55 55 05 0b ff 64 00"), t)), "") << "speed";
  EXPECT_EQ(hex_of(exchange(emu, hex("55 55 03 1c 01"), t)), "") << "bus servo info";
  EXPECT_EQ(hex_of(exchange(emu, download_action(1, 2, 1, 300, 3, 1900), t)), "55 55 02 19");
  EXPECT_EQ(emu.stored_count(1), 2);
  EXPECT_EQ((*emu.stored_group(1))[0].servos, (std::vector<lsc6::Target>{{3, 1100}}));
}

TEST(Lsc6ReceiverStates, ALenOf254MidDownloadSwallowsTheNextIndexUntilTheCounterWraps) {
  Lsc6Emulator emu(unpaced());
  io::TimePoint t = at_ms(0);
  ASSERT_EQ(hex_of(exchange(emu, download_action(2, 2, 0, 100, 1, 1500), t)), "55 55 02 19");
  Bytes wedge = hex("55 55 fe 19");
  const Bytes next = download_action(2, 2, 1, 100, 6, 2500);
  wedge.insert(wedge.end(), next.begin(), next.end());
  EXPECT_EQ(hex_of(exchange(emu, wedge, t)), "") << "index 1 is swallowed";
  EXPECT_TRUE(emu.receiver_wedged());
  EXPECT_EQ(emu.stored_count(2), 0) << "the last index never arrived";
  // 17 bytes so far: 242 more bring the counter round to position 2, read as a new LEN (00:
  // abandoned).
  EXPECT_EQ(hex_of(exchange(emu, Bytes(242, 0x00), t)), "");
  EXPECT_FALSE(emu.receiver_wedged());
  EXPECT_EQ(hex_of(exchange(emu, next, t)), "55 55 02 19");
  EXPECT_EQ(emu.stored_count(2), 2);
}

TEST(Lsc6ReceiverStates, AHalfReceivedFrameTakesTheNextHeaderAsItsData) {
  Lsc6Emulator emu(unpaced());
  io::TimePoint t = at_ms(0);
  ASSERT_EQ(hex_of(exchange(emu, download_action(7, 1, 0, 100, 1, 900), t)), "55 55 02 19");
  // Half a Run (55 55 05 06 00), then an erase: the erase's 55 55 completes the Run (group 0,
  // times 0x5555; group 0 is empty, so it is answered and nothing plays); 02 08 is noise.
  EXPECT_EQ(hex_of(exchange(emu, hex("55 55 05 06 00"), t)), "");
  EXPECT_EQ(hex_of(exchange(emu, hex("55 55 02 08"), t)), "55 55 02 06");
  EXPECT_EQ(emu.stored_count(7), 1) << "no erase happened";
  ASSERT_EQ(emu.received().size(), 2u);
  EXPECT_EQ(hex_of(emu.received()[1].raw), "55 55 05 06 00 55 55");
}

}  // namespace
}  // namespace seqc::emu::test
