// The LSC-6 firmware emulator: its receiver, its answers and their timing, its flash and its
// player, against request bytes written by hand (docs/protocol/lsc-6.md).
#include <gtest/gtest.h>

#include "tests/emulator/lsc6_test_util.hpp"

namespace seqc::emu::test {
namespace {

TEST(Lsc6Emulator, StoresEachActionAndAnswersEveryFrame) {
  Lsc6Emulator emu(unpaced());
  io::TimePoint t = at_ms(0);
  EXPECT_EQ(hex_of(exchange(emu, download_action(2, 2, 0, 500, 1, 1500), t)), "55 55 02 19");
  EXPECT_EQ(emu.stored_count(2), 0) << "the count is written only with the last index";
  EXPECT_EQ(hex_of(exchange(emu, download_action(2, 2, 1, 700, 6, 2500), t)), "55 55 02 19");
  EXPECT_EQ(emu.stored_count(2), 2);
  const auto stored = emu.stored_group(2);
  ASSERT_TRUE(stored.has_value());
  ASSERT_EQ(stored->size(), 2u);
  EXPECT_EQ((*stored)[0].time_ms, 500);
  EXPECT_EQ((*stored)[0].servos, (std::vector<lsc6::Target>{{1, 1500}}));
  EXPECT_EQ((*stored)[1].servos, (std::vector<lsc6::Target>{{6, 2500}}));
}

TEST(Lsc6Emulator, TheFirstIndexErasesTheGroupBeforeAnswering) {
  Lsc6Emulator emu(unpaced());  // 45 ms per sector erase, 0.7 ms per slot, 1.4 ms per table
  emu.receive(download_action(0, 2, 0, 100, 1, 1500), at_ms(0));
  EXPECT_EQ(emu.next_output_at(), at_ms(180) + 700us) << "four sector erases, one slot";
  (void)emu.take_output(at_ms(1000));
  emu.receive(download_action(0, 2, 1, 100, 1, 1600), at_ms(1000));
  EXPECT_EQ(emu.next_output_at(), at_ms(1000) + 700us + 45ms + 1400us)
      << "a slot, then the count table's sector erase and write";
}

TEST(Lsc6Emulator, HoldsOneFrameWhileBusyAndDropsTheNext) {
  Lsc6Emulator emu(unpaced());
  Bytes three = download_action(0, 3, 0, 100, 1, 1500);
  const Bytes b = download_action(0, 3, 1, 100, 1, 1600);
  const Bytes c = download_action(0, 3, 2, 100, 1, 1700);
  three.insert(three.end(), b.begin(), b.end());
  three.insert(three.end(), c.begin(), c.end());
  io::TimePoint t = at_ms(0);
  EXPECT_EQ(hex_of(exchange(emu, three, t)), "55 55 02 19 55 55 02 19")
      << "the first is processed, the second held, the third lost";
  ASSERT_EQ(emu.received().size(), 3u);
  EXPECT_FALSE(emu.received()[1].dropped_busy);
  EXPECT_TRUE(emu.received()[2].dropped_busy);
  EXPECT_EQ(emu.stored_count(0), 0) << "the last index never arrived";
}

TEST(Lsc6Emulator, AnInterruptedDownloadLeavesTheOldCountOverErasedActions) {
  Lsc6Emulator emu(unpaced());
  io::TimePoint t = at_ms(0);
  for (unsigned i = 0; i < 3; ++i)
    (void)exchange(emu, download_action(1, 3, i, 100, 2, 1000 + i), t);
  ASSERT_EQ(emu.stored_count(1), 3);
  (void)exchange(emu, download_action(1, 3, 0, 100, 2, 2000), t);
  (void)exchange(emu, download_action(1, 3, 1, 100, 2, 2100), t);
  EXPECT_EQ(emu.stored_count(1), 3) << "the old count stays";
  // Playing it runs the two new actions, then reads an erased slot (N = 0xff) and stops.
  t += 1s;
  EXPECT_EQ(hex_of(exchange(emu, frame(0x06, {0x01, 0x01, 0x00}), t)), "55 55 02 06")
      << "no finish notice: the player stopped at the erased action";
  EXPECT_EQ(emu.playing_group(), std::nullopt);
  EXPECT_EQ(emu.pulse(2, t), 2100);
}

TEST(Lsc6Emulator, RunAnswersFirstAndAnnouncesTheEnd) {
  Lsc6Emulator emu(unpaced());
  io::TimePoint t = at_ms(0);
  (void)exchange(emu, download_action(0, 2, 0, 400, 3, 900), t);
  (void)exchange(emu, download_action(0, 2, 1, 600, 3, 2100), t);
  const io::TimePoint start = t;
  emu.receive(hex("55 55 05 06 00 02 00"), start);  // group 0, twice
  EXPECT_EQ(hex_of(emu.take_output(start)), "55 55 02 06");
  EXPECT_EQ(emu.playing_group(), 0);
  EXPECT_EQ(hex_of(emu.take_output(start + 1999ms)), "");
  EXPECT_EQ(hex_of(emu.take_output(start + 2000ms)), "55 55 02 07") << "2 x (400 + 600) ms";
  EXPECT_EQ(emu.pulse(3, start + 2000ms), 2100);
}

TEST(Lsc6Emulator, CopiesThatNeverAnswerRunOrAnnounceTheEnd) {
  Lsc6Config config = unpaced();
  ASSERT_TRUE(apply_lsc6_options("no-run-reply,no-finish", config).ok());
  Lsc6Emulator emu(config);
  io::TimePoint t = at_ms(0);
  (void)exchange(emu, download_action(0, 1, 0, 100, 1, 900), t);
  EXPECT_EQ(hex_of(exchange(emu, hex("55 55 05 06 00 01 00"), t, 5s)), "");
  EXPECT_EQ(emu.pulse(1, t + 5s), 900) << "it played all the same";
}

TEST(Lsc6Emulator, EraseWipesEveryGroup) {
  Lsc6Emulator emu(unpaced());
  io::TimePoint t = at_ms(0);
  (void)exchange(emu, download_action(0, 1, 0, 100, 1, 900), t);
  (void)exchange(emu, download_action(7, 1, 0, 100, 1, 900), t);
  EXPECT_EQ(hex_of(exchange(emu, hex("55 55 03 08 07"), t)), "55 55 02 08")
      << "the parameter names group 7, but every group goes";
  EXPECT_EQ(emu.stored_count(0), 0);
  EXPECT_EQ(emu.stored_count(7), 0);
}

TEST(Lsc6Emulator, IgnoresCommandsItDoesNotKnow) {
  Lsc6Emulator emu(unpaced());
  io::TimePoint t = at_ms(0);
  EXPECT_EQ(hex_of(exchange(emu, hex("55 55 02 0f"), t)), "") << "no battery command";
  EXPECT_EQ(hex_of(exchange(emu, hex("55 55 05 0b ff 64 00"), t)), "") << "no speed command";
  EXPECT_EQ(hex_of(exchange(emu, hex("55 55 02 08"), t)), "55 55 02 08") << "still listening";
}

TEST(Lsc6Emulator, MovesOnlyWiredChannelsWithinRange) {
  Lsc6Emulator emu(unpaced());
  // time 5 ms (clamped to 20), ch1 -> 2000, ch2 -> 2600 (out of range: ignored)
  emu.receive(hex("55 55 0b 03 02 05 00 01 d0 07 02 28 0a"), at_ms(0));
  emu.advance_to(at_ms(10));
  EXPECT_EQ(emu.pulse(1, at_ms(10)), 1750) << "half way through the clamped 20 ms";
  EXPECT_EQ(emu.pulse(1, at_ms(20)), 2000);
  EXPECT_EQ(emu.pulse(2, at_ms(20)), 1500);
}

TEST(Lsc6Emulator, ALenOf254SwallowsWhatFollowsUntilTheCounterWraps) {
  Lsc6Emulator emu(unpaced());
  io::TimePoint t = at_ms(0);
  (void)exchange(emu, hex("55 55 fe 08"), t);
  EXPECT_TRUE(emu.receiver_wedged());
  EXPECT_EQ(hex_of(exchange(emu, hex("55 55 02 08"), t)), "") << "swallowed";
  // 8 bytes so far: counter 8. 248 more bring it to 0, then positions 0, 1 and 2: the byte at
  // position 2 is read as a new LEN; 00 abandons the frame.
  (void)exchange(emu, Bytes(248 + 3, 0x00), t);
  EXPECT_FALSE(emu.receiver_wedged());
  EXPECT_EQ(hex_of(exchange(emu, hex("55 55 02 08"), t)), "55 55 02 08");
}

TEST(Lsc6Emulator, APowerCycleFreesASwallowingReceiver) {
  Lsc6Emulator emu(unpaced());
  io::TimePoint t = at_ms(0);
  (void)exchange(emu, hex("55 55 ff 08 01 02"), t);
  EXPECT_TRUE(emu.receiver_wedged());
  emu.power_cycle(t);
  EXPECT_EQ(hex_of(exchange(emu, hex("55 55 02 08"), t)), "55 55 02 08");
}

TEST(Lsc6Emulator, ALenBelowTwoIsAbandoned) {
  Lsc6Emulator emu(unpaced());
  io::TimePoint t = at_ms(0);
  EXPECT_EQ(hex_of(exchange(emu, hex("55 55 01 55 55 02 08"), t)), "55 55 02 08");
}

TEST(Lsc6Emulator, WaitsForTheRestOfAFrameHoweverLong) {
  Lsc6Emulator emu(unpaced());
  const Bytes request = hex("55 55 02 08");
  io::TimePoint t = at_ms(0);
  for (std::uint8_t b : request) {
    emu.receive(ByteView(&b, 1), t);
    t += 2s;
  }
  EXPECT_EQ(hex_of(emu.take_output(t + 1s)), "55 55 02 08") << "no inter-byte timeout";
}

TEST(Lsc6Emulator, AnotherGroupCannotInterruptButGroupZeroCan) {
  Lsc6Emulator emu(unpaced());
  io::TimePoint t = at_ms(0);
  (void)exchange(emu, download_action(0, 1, 0, 1000, 1, 900), t);
  (void)exchange(emu, download_action(1, 1, 0, 1000, 1, 2000), t);
  (void)exchange(emu, download_action(2, 1, 0, 1000, 1, 1200), t);
  emu.receive(hex("55 55 05 06 01 00 00"), t);  // group 1 forever
  emu.receive(hex("55 55 05 06 02 01 00"), t + 100ms);
  emu.advance_to(t + 200ms);
  EXPECT_EQ(emu.playing_group(), 1) << "a run of group 2 is ignored while group 1 plays";
  emu.receive(hex("55 55 05 06 00 01 00"), t + 300ms);
  emu.advance_to(t + 400ms);
  EXPECT_EQ(emu.playing_group(), 0);
}

TEST(Lsc6Emulator, AnActionWithMoreThanEightServosStopsThePlayer) {
  Lsc6Emulator emu(unpaced());
  io::TimePoint t = at_ms(0);
  Bytes nine{0x00, 0x01, 0x00, 0x09, 0x64, 0x00};
  for (int i = 0; i < 9; ++i) {
    nine.push_back(static_cast<std::uint8_t>(1 + i % 6));
    nine.push_back(0xdc);
    nine.push_back(0x05);
  }
  EXPECT_EQ(hex_of(exchange(emu, frame(0x19, nine), t)), "55 55 02 19");
  EXPECT_EQ(hex_of(exchange(emu, hex("55 55 05 06 00 01 00"), t)), "55 55 02 06");
  EXPECT_EQ(emu.playing_group(), std::nullopt);
}

TEST(Lsc6Emulator, PacedAnswersTakeTheirWireTime) {
  Lsc6Emulator emu;  // 9600 baud
  emu.receive(hex("55 55 02 08"), at_ms(0));
  const io::Duration byte{10'000'000'000LL / 9600};
  EXPECT_EQ(emu.next_message_end_at(), at_ms(45) + 1400us + 4 * byte);
}

TEST(Lsc6Options, NamesTheBadItem) {
  Lsc6Config c;
  auto st = apply_lsc6_options("drop=2", c);
  ASSERT_FALSE(st.ok());
  EXPECT_EQ(st.error().message, "emu:lsc6 option 'drop=2': expected a fraction 0..1");
  EXPECT_FALSE(apply_lsc6_options("busy=1", c).ok());
  EXPECT_TRUE(apply_lsc6_options("drop=0.1,seed=9,baud=115200", c).ok());
  EXPECT_EQ(c.baud, 115200u);
}

}  // namespace
}  // namespace seqc::emu::test
